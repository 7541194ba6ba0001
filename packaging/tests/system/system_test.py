#!/usr/bin/env python3
"""The package's system test: the Debian package booted as a museum boots it, each
deployment scenario checked, one line each (`ok NAME (seconds): what was seen` or
`FAIL NAME: why`), then the timings. run.sh builds the package and the image and calls this.

  system_test.py --image DIR --out DIR [--only NAME[,NAME…]] [--accel tcg|kvm]
                 [--suite bookworm|trixie] [--reference FILE] [--screens DIR] [--attach]

--suite: the Debian release the image is (first-boot checks the guest's /etc/os-release).

--attach drives a machine already running with its sockets in --out (one that run.sh --keep
left, restarted by hand): for working on a scenario without booting again.
"""

import argparse
import json
import os
import re
import shlex
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from vm import (Machine, VmError, signature, signature_distance, wav_channels_energy,  # noqa: E402
                wav_seconds, write_png)

UNIT = "mallet"
SETTINGS = "/etc/mallet/mallet.toml"
# A broken settings file: the operator's own file with a line that is not TOML (a broken
# drop-in alone is only skipped, the rest loads).
BREAK_SETTINGS = f"cp {SETTINGS} /root/mallet.toml.good && printf '\\n[audio\\n' >> {SETTINGS}"
MEND_SETTINGS = f"cp /root/mallet.toml.good {SETTINGS}"
SCENARIOS = ["first-boot", "mouse", "reload", "bad-settings", "watchdog", "state-full", "quit", "update",
             "wiimote", "remote-off-on", "camera", "reboot"]


class Test:
    def __init__(self, args):
        self.args = args
        self.vm = Machine(args.image, args.out, args.accel)
        self.timings = []
        self.results = []

    # --- the guest ----------------------------------------------------------------------
    def sh(self, command, timeout=120, check=False):
        return self.vm.agent.run(command, timeout=timeout, check=check)

    def out(self, command, timeout=120):
        return self.sh(command, timeout=timeout, check=True)[1].strip()

    def unit(self, name=UNIT):
        text = self.out(f"systemctl show {name} -p ActiveState -p SubState -p MainPID -p NRestarts")
        return dict(line.split("=", 1) for line in text.splitlines() if "=" in line)

    def wait(self, what, predicate, timeout, step=2.0):
        """Polls predicate() until it returns something true; VmError naming `what` after
        `timeout` seconds. Returns what it returned and the seconds waited."""
        start = time.monotonic()
        last = None
        while True:
            try:
                last = predicate()
            except VmError as e:
                last = None
                why = str(e)
            else:
                why = ""
            if last:
                return last, time.monotonic() - start
            if time.monotonic() - start > timeout:
                raise VmError(f"{what}: not within {timeout} s{' (' + why + ')' if why else ''}")
            time.sleep(step)

    def wait_active(self, timeout, name=UNIT, not_pid=None):
        def active():
            u = self.unit(name)
            if u.get("ActiveState") == "active" and u.get("MainPID", "0") != "0" and u.get("MainPID") != not_pid:
                return u
            return None
        try:
            return self.wait(f"{name}.service active", active, timeout)
        except VmError as e:
            raise VmError(f"{e}; {self.diagnosis()}")

    def guest_time(self):
        return self.out("date +%s.%N")

    def journal(self, since, unit=UNIT, grep=None):
        command = f"journalctl -u {unit} --since @{since} -o cat --no-pager"
        if grep:
            command += f" | grep -E {shlex.quote(grep)}"
        return self.sh(command)[1]

    def diagnosis(self):
        """The last lines a failing check should show."""
        _, status = self.sh(f"systemctl status {UNIT} mallet-session --no-pager -n 0 2>&1 | head -n 20; "
                            "journalctl -b --no-pager -n 25 -o short-monotonic 2>&1")
        return "guest says:\n" + status

    def failure_journal(self, name, since):
        """A failed scenario's journal (every unit, since it began) in OUT/journal-NAME.txt, and
        its last lines from the kiosk and the test's own units on the output, where a CI log
        shows them (a later reboot's journal.txt no longer holds this boot)."""
        try:
            _, text = self.sh(f"journalctl --since @{since} -o short-monotonic --no-pager", timeout=300)
            with open(os.path.join(self.args.out, f"journal-{name}.txt"), "w") as f:
                f.write(text)
            for unit, lines in ((UNIT, 40), ("wiimote-emulator", 15)):
                tail = self.sh(f"journalctl -u {unit} --since @{since} -o short-monotonic --no-pager "
                               f"| grep -v ' strike t=' | tail -n {lines}", timeout=120)[1].rstrip()
                if tail and "-- No entries --" not in tail:
                    print(f"  {unit}, last lines of the scenario:", flush=True)
                    print("\n".join("  | " + l for l in tail.splitlines()), flush=True)
        except Exception as e:  # the machine may be the reason the scenario failed
            print(f"system: could not save {name}'s journal: {e}", flush=True)

    def screen(self, name):
        path = os.path.join(self.args.out, name + ".ppm")
        width, height, rgb = self.vm.qmp.screendump(path)
        png = os.path.join(self.args.out, name + ".png")
        write_png(png, width, height, rgb)
        if self.args.screens:
            os.makedirs(self.args.screens, exist_ok=True)
            write_png(os.path.join(self.args.screens, name + ".png"), width, height, rgb)
        return width, height, rgb

    # --- the scenarios ------------------------------------------------------------------
    def first_boot(self):
        """Power-on → the kiosk on the screen, as a museum's first boot."""
        seconds = self.vm.wait_for_agent(900)
        self.timings.append(("power-on → guest agent (booted)", seconds))
        u, waited = self.wait_active(900)
        to_active = time.monotonic() - self.vm.started
        self.timings.append(("power-on → mallet.service active (READY=1 after the second frame)", to_active))
        mono = dict(line.split("=", 1) for line in self.out(
            "systemctl show mallet -p ExecMainStartTimestampMonotonic -p ActiveEnterTimestampMonotonic "
            "-p InactiveExitTimestampMonotonic").splitlines())
        start_us = int(mono["InactiveExitTimestampMonotonic"])
        ready_us = int(mono["ActiveEnterTimestampMonotonic"])
        self.timings.append(("guest: kernel start → mallet.service started", start_us / 1e6))
        self.timings.append(("guest: mallet.service started → READY=1 (its second frame)", (ready_us - start_us) / 1e6))
        problems = []
        # The release the image was made of, and its cage (0.1.4 on Debian 12, whose abort at
        # a stop mallet-session takes for a clean stop; 0.2.0 on Debian 13).
        release = self.out(". /etc/os-release && echo \"$VERSION_CODENAME $VERSION_ID\"").split()
        cage = self.out("cage -v 2>&1 | head -n 1").replace("Cage version ", "cage ")
        if self.args.suite and (not release or release[0] != self.args.suite):
            problems.append(f"the guest is Debian {' '.join(release) or '?'}, not {self.args.suite}")
        system = f"Debian {release[1] if len(release) > 1 else '?'} ({release[0] if release else '?'}), {cage}"
        # The display is a logind seat session of the kiosk's user, active on seat0.
        sessions = self.out("loginctl list-sessions --no-legend")
        if not re.search(r"\bmallet\b.*\bseat0\b", sessions):
            problems.append(f"no seat0 session of mallet in loginctl: {sessions!r}")
        # Watched by its watchdog.
        watchdog = self.out("systemctl show mallet -p WatchdogUSec --value")
        if watchdog in ("", "0", "infinity"):
            problems.append(f"no watchdog (WatchdogUSec={watchdog})")
        # The kiosk's own lines are the unit's: `journalctl -u mallet` shows them.
        lines = self.journal(0, grep="^mallet run: |^input: ")
        if "mallet run:" not in lines:
            problems.append("journalctl -u mallet shows none of the kiosk's lines")
        # Mesa's shader cache is written (the sandbox leaves it a writable folder).
        cache = self.out("find /var/cache/mallet/mesa_shader_cache -type f 2>/dev/null | wc -l")
        if cache == "0":
            problems.append("Mesa's shader cache /var/cache/mallet/mesa_shader_cache is empty")
        # The session's own lines are its scope's, not the unit's: read by their identifier.
        renderer = self.sh("journalctl -b -t mallet-session -o cat --no-pager | grep 'compositor renderer'")[1]
        renderer = renderer.strip().splitlines()
        doctor_says = self.out("runuser -u mallet -- mallet doctor --print-renderer", timeout=300)
        if not renderer or not renderer[-1].endswith(doctor_says):
            problems.append(f"the session chose {renderer[-1] if renderer else 'no renderer'}, "
                            f"mallet doctor --print-renderer says {doctor_says}")
        # The kiosk alone: the machine has neither the package mallet-bench nor a library only
        # the benchmarks link (XTest, STK), and the kiosk ran without them; `mallet bench` says
        # in one line which package to install.
        libraries = self.out("ldd /usr/bin/mallet")
        for wanted_absent in ("libXtst", "libstk", "not found"):
            if wanted_absent in libraries:
                problems.append(f"ldd /usr/bin/mallet shows {wanted_absent}: {libraries}")
        status, said = self.sh("mallet bench report --quick 2>&1")
        if status != 1 or "install the Debian package mallet-bench" not in said:
            problems.append(f"mallet bench without mallet-bench: status {status}: {said.strip()}")
        time.sleep(10)  # a few frames at TCG's pace
        # A PC without a GPU driver (virtio-gpu without 3D: lavapipe): only each frame's changed
        # pixels are put into Xwayland's window (render/x11_image_put), and the kiosk paces them.
        paced = self.journal(0, grep="^render: frames").strip().splitlines()
        if not paced or "only the changed pixels, put into the X11 window" not in paced[-1]:
            problems.append(f"the kiosk's frames are not put as changed pixels: {paced[-1] if paced else 'no line'}")
        width, height, rgb = self.screen("vm-first-boot")
        sig = signature(width, height, rgb)
        bright = sum(sum(c) for c in sig) / (3 * len(sig))
        if bright < 12:
            problems.append(f"the screen is dark (mean level {bright:.0f} of 255)")
        reference = self.args.reference
        distance = None
        if reference and os.path.exists(reference):
            with open(reference) as f:
                distance = signature_distance(sig, json.load(f))
            if distance > 30:
                problems.append(f"the screen differs from {reference} by {distance:.1f} levels on average (at most 30)")
        elif reference:
            with open(reference, "w") as f:
                json.dump(sig, f)
        if problems:
            raise VmError("; ".join(problems))
        return (f"{system}; active after {waited:.0f} s of waiting, {u['MainPID']} is the kiosk; screen {width}x{height}, "
                f"{'distance %.1f from the reference' % distance if distance is not None else 'reference written'}; "
                f"{renderer[-1] if renderer else 'no renderer line'}; {paced[-1] if paced else 'no pace line'}")

    def mouse(self):
        """A visitor's downstroke with a USB mouse reaches the kiosk through evdev."""
        since = self.guest_time()
        line = self.journal(0, grep="^input: ").strip().splitlines()
        if not line or "evdev" not in line[-1]:
            raise VmError(f"the kiosk's input is not the mouse through evdev: {line[-1] if line else 'no input line'}")
        wav_before = wav_seconds(self.vm.wav)
        qmp = self.vm.qmp
        w, h = self.vm.screen
        for fx in (0.22, 0.3, 0.38, 0.62, 0.7, 0.78):
            qmp.move(-4 * w, -4 * h)  # the top-left corner
            time.sleep(0.2)
            qmp.move(int(fx * w), 0)
            time.sleep(0.5)
            for _ in range(12):  # down the whole screen in about 0.15 s
                qmp.move(0, h // 10)
                time.sleep(0.012)
            time.sleep(1.0)
        strikes, waited = self.wait("a strike in journalctl -u mallet after the mouse's downstrokes",
                                    lambda: self.journal(since, grep="^strike t=").strip().splitlines(), 180)
        # The visitor took over from the attract mode's ghost: the next heartbeat (one a minute)
        # says play. The visitor stays (the mouse nudged now and then), or the kiosk would go
        # back to its attract mode before the heartbeat comes. A nudge is real movement only
        # past the kiosk's dead band (0.005 of the screen: 2 px at 576 was not, and the scenario
        # passed only when a heartbeat fell within the 45 s idle rule after the last stroke);
        # sideways, so that it strikes nothing, and one way a look (the kiosk draws a frame every
        # second or so under TCG: there and back within one would be no movement at all).
        nudge = [max(12, int(0.012 * w))]
        def still_playing():
            qmp.move(nudge[0], 0)
            nudge[0] = -nudge[0]
            return self.journal(since, grep="^heartbeat: play").strip()
        beat, _ = self.wait("a heartbeat saying play after the mouse's downstrokes", still_playing, 150)
        self.screen("vm-play")
        rate, left, right = wav_channels_energy(self.vm.wav, wav_before)
        if left < 30 or right < 30:
            raise VmError(f"the WAV after the strokes is silent on a channel: RMS {left:.0f} / {right:.0f} "
                          f"(16-bit) at {rate} Hz")
        # Underruns are many under TCG; none may end the kiosk (alsa-lib's snd_pcm_plugin_status
        # assert above dmix did, through the default PCM's softvol): the kiosk opens dmix itself.
        device = re.search(r"audio: ([^,]+),", self.journal(0, grep="^mallet run: ").strip().splitlines()[-1])
        aborts = self.journal(0, grep="Assertion").strip()
        restarts = self.unit()["NRestarts"]
        if restarts != "0" or aborts:
            raise VmError(f"the kiosk restarted {restarts} time(s) since boot: {aborts or 'see journal.txt'}")
        if not device or device.group(1) != "dmix":
            raise VmError(f"the kiosk's sound is not ALSA's dmix itself: {device.group(1) if device else 'no line'}")
        xruns = re.search(r"xruns (\d+)", beat)
        return (f"{len(strikes)} strike(s), first: {strikes[0]}; {beat.splitlines()[0]}; "
                f"WAV RMS left {left:.0f}, right {right:.0f}; through dmix, "
                f"{xruns.group(1) if xruns else 'some'} underruns, no restart")

    def reload(self):
        """`systemctl reload` with a broken settings file is refused; the kiosk plays on."""
        before = self.unit()
        since = self.guest_time()
        self.out(BREAK_SETTINGS)
        try:
            self.out("systemctl reload mallet")
            refused, _ = self.wait("the kiosk's refusal in journalctl -u mallet",
                                   lambda: self.journal(since, grep="reload refused").strip(), 180)
        finally:
            self.out(f"{MEND_SETTINGS} && systemctl reload mallet")
        # A reload keeps the unit "reloading" until the kiosk says READY=1 again.
        after, _ = self.wait_active(300)
        if after["MainPID"] != before["MainPID"]:
            raise VmError(f"the kiosk did not play on: {before} → {after}")
        if "mallet.toml" not in refused:
            raise VmError(f"the refusal does not name the file: {refused}")
        return refused.splitlines()[0]

    def bad_settings(self):
        """A broken settings file at boot: the kiosk still comes up, and says what is wrong."""
        since = self.guest_time()
        self.out(BREAK_SETTINGS)
        old = self.unit()["MainPID"]
        try:
            self.out("systemctl restart mallet", timeout=600)
            u, waited = self.wait_active(600, not_pid=old)
            said = self.journal(since, grep="settings refused").strip().splitlines()
        finally:
            self.out(MEND_SETTINGS)
        if not said or "mallet.toml" not in said[0]:
            raise VmError(f"the kiosk came up but no line names the broken file: {said}")
        self.out("systemctl restart mallet", timeout=600)
        self.wait_active(600, not_pid=u["MainPID"])
        return f"came up; said: {said[0]}"

    def watchdog(self):
        """A stopped kiosk (kill -STOP) is killed by the watchdog and started again."""
        before = self.unit()
        since = self.guest_time()
        self.out(f"kill -STOP {before['MainPID']}")
        u, waited = self.wait_active(600, not_pid=before["MainPID"])
        said = self.sh(f"journalctl -u mallet --since @{since} -o cat --no-pager | grep -i watchdog")[1].strip()
        if not said:
            raise VmError("restarted, but systemd logged no watchdog time-out")
        return f"restarted as {u['MainPID']} after {waited:.0f} s: {said.splitlines()[0]}"

    def state_full(self):
        """/var/lib/mallet full: the kiosk plays on, and says so."""
        since = self.guest_time()
        self.out("mount -t tmpfs -o size=64k,mode=0755 tmpfs /var/lib/mallet && chown mallet:mallet /var/lib/mallet "
                 "&& (dd if=/dev/zero of=/var/lib/mallet/filler bs=4k 2>/dev/null; true)")
        try:
            old = self.unit()["MainPID"]
            self.out("systemctl restart mallet")
            u, waited = self.wait_active(600, not_pid=old)
            time.sleep(20)
            still = self.unit()
            said = self.journal(since, grep="/var/lib/mallet").strip().splitlines()
        finally:
            self.sh("systemctl stop mallet; umount /var/lib/mallet; systemctl start mallet", timeout=300)
        if still["MainPID"] != u["MainPID"] or still["ActiveState"] != "active":
            raise VmError(f"the kiosk did not play on with its state folder full: {u} → {still}")
        if not said:
            raise VmError("the kiosk played on but said nothing about /var/lib/mallet")
        self.wait_active(600)
        return f"played on; said: {said[0]}"

    def wiimote(self):
        """The emulated Wii Remote on /dev/uhid, bound by the kernel's hid-wiimote."""
        emulator = "/opt/mallet-test/wiimote_uhid.py"
        if self.sh(f"test -x {emulator} || test -f {emulator}")[0] != 0:
            raise VmError(f"no {emulator} in the image")
        since = self.guest_time()
        self.sh("systemctl stop wiimote-emulator 2>/dev/null; systemctl reset-failed wiimote-emulator 2>/dev/null")
        self.out(f"systemd-run --unit wiimote-emulator python3 {emulator} --calibration --strokes 40")
        bound, _ = self.wait("a hidraw node of the emulated remote, bound by hid-wiimote",
                             lambda: self.out("for d in /sys/class/hidraw/hidraw*; do "
                                              "grep -l 057E:0306 $d/device/uevent 2>/dev/null; done; "
                                              "ls -l /sys/bus/hid/drivers/wiimote/ 2>/dev/null | grep -c 057E"), 120)
        # With `[input] source = "auto"` the kiosk takes the remote it finds at its start (a
        # museum switches the remote on before the PC): started again, as at the next boot.
        old = self.unit()["MainPID"]
        self.out("systemctl restart mallet", timeout=600)
        self.wait_active(600, not_pid=old)
        connected, _ = self.wait("'Wii Remote … connected' in journalctl -u mallet",
                                 lambda: self.journal(since, grep="Wii Remote .* connected").strip(), 300)
        calibrated, _ = self.wait("the calibration's end in journalctl -u mallet",
                                  lambda: self.journal(since, grep="^Calibrated: .*saved|calibration: (done|saved|complete)").strip(), 900)
        strikes, _ = self.wait("strikes with the remote",
                               lambda: self.journal(since, grep="^strike t=").strip().splitlines(), 600)
        # The doctor's remote checks beside the playing kiosk (--only: its vulkan check draws
        # and times frames of its own, 166 s of a loaded guest once, and is not what is asked).
        doctor_from = time.monotonic()
        code, doctor = self.sh("runuser -u mallet -- mallet doctor --only wiimote,hidraw 2>&1", timeout=300)
        doctor_s = time.monotonic() - doctor_from
        lines = [l for l in doctor.splitlines() if re.search(r"wiimote|hidraw", l)]
        bad = [l for l in lines if not l.startswith("ok")]
        if not lines or bad:
            raise VmError(f"mallet doctor on the remote: {lines or doctor[-300:]}")
        return (f"{connected.splitlines()[0]}; {calibrated.splitlines()[0]}; {len(strikes)} strike(s); "
                f"doctor ({doctor_s:.0f} s): {' | '.join(lines)}")

    def remote_off_on(self):
        """The remote switched off and on again: the kiosk reconnects."""
        if self.sh("systemctl is-active wiimote-emulator")[0] != 0:
            raise VmError("the emulated remote is not running (the wiimote scenario comes first)")
        since = self.guest_time()
        self.out("systemctl kill -s USR1 wiimote-emulator")
        lost, _ = self.wait("'Wii Remote … lost'", lambda: self.journal(since, grep="Wii Remote .* lost").strip(), 180)
        since2 = self.guest_time()
        self.out("systemctl kill -s USR2 wiimote-emulator")
        back, _ = self.wait("'Wii Remote … connected' again",
                            lambda: self.journal(since2, grep="Wii Remote .* connected").strip(), 300)
        return f"{lost.splitlines()[0]}; {back.splitlines()[0]}"

    def camera(self):
        """A V4L2 camera as the IR tracker: the kernel's vivid driver as the camera (its
        capture node only), listed and monitored, the kiosk streaming from it, unplugged
        (vivid's Disconnect) and back, and the doctor's camera check."""
        dropin = "/etc/mallet/mallet.toml.d/50-camera-test.toml"
        self.out("modprobe vivid node_types=0x1 n_devs=1 && udevadm settle", timeout=120)
        node, _ = self.wait("a vivid /dev/video node",
                            lambda: self.out("grep -l vivid /sys/class/video4linux/video*/name 2>/dev/null | head -1"), 60)
        node = "/dev/" + node.split("/")[-2]
        listed = self.out("runuser -u mallet -- mallet camera list")
        if node not in listed or "vivid" not in listed:
            raise VmError(f"mallet camera list does not show {node} (vivid): {listed[-400:]}")
        code, mon = self.sh(f"runuser -u mallet -- mallet camera monitor --seconds 4 --device {node}", timeout=180)
        summary = [l.strip() for l in mon.splitlines() if "rate achieved" in l or "stamping" in l or "summary" in l]
        if code != 0 or "streaming" not in mon or len(summary) < 3:
            raise VmError(f"mallet camera monitor on vivid exited {code}: {mon[-600:]}")
        if "the kernel's stamp" not in mon:
            raise VmError(f"the frames are not stamped by the kernel: {summary}")
        since = self.guest_time()
        self.out(f"mkdir -p {os.path.dirname(dropin)} && printf '[input]\\nsource = \"camera\"\\n[camera]\\ndevice = \"{node}\"\\nwidth = 320\\n"
                 f"height = 180\\nrate_hz = 30\\n' > {dropin}")
        try:
            old = self.unit()["MainPID"]
            self.out("systemctl restart mallet", timeout=600)
            self.wait_active(600, not_pid=old)
            connected, _ = self.wait("'camera … connected' in journalctl -u mallet",
                                     lambda: self.journal(since, grep="camera .* connected").strip(), 300)
            since2 = self.guest_time()
            self.out(f"python3 /opt/mallet-test/v4l2_disconnect.py {node}")
            try:
                lost, _ = self.wait("'camera … lost' after vivid's Disconnect",
                                    lambda: self.journal(since2, grep="camera .* lost").strip(), 180)
            except VmError as e:
                # What the driver did (its disconnect, and its reconnect once the last handle closed).
                kernel = self.sh(f"journalctl -k --since @{since2} -o short-monotonic --no-pager | grep -i vivid")[1]
                raise VmError(f"{e}; the kernel said: {kernel.strip()[-600:] or 'nothing of vivid'}") from None
            back, _ = self.wait("'camera … connected' again",
                                lambda: self.journal(since2, grep="camera .* connected").strip(), 300)
            if self.unit()["ActiveState"] != "active":
                raise VmError("the kiosk did not play on through the camera's unplugging")
            # The doctor beside the running kiosk: the camera is the kiosk's (one program
            # streams from a V4L2 node), and it says so; with the kiosk stopped it opens it.
            def camera_line():
                doctor = self.sh("runuser -u mallet -- mallet doctor --only camera 2>&1", timeout=300)[1]
                found = [l for l in doctor.splitlines() if re.match(r"^(ok|warn|fail)\s+camera\b", l)]
                return found[0] if found else doctor[-400:]
            busy = camera_line()
            if not busy.startswith("warn") or "in use by another program" not in busy:
                raise VmError(f"mallet doctor's camera check beside the kiosk: {busy}")
            self.out("systemctl stop mallet", timeout=300)
            alone = camera_line()
            if alone.startswith("fail") or "frames/s achieved" not in alone:
                raise VmError(f"mallet doctor's camera check: {alone}")
            line = [busy, alone]
        finally:
            self.sh(f"rm -f {dropin}; systemctl restart mallet", timeout=600)
        self.wait_active(600)
        return (f"{summary[0]}; {'; '.join(summary[1:])}; {connected.splitlines()[0]}; {lost.splitlines()[0]}; "
                f"{back.splitlines()[-1]}; doctor beside the kiosk: {line[0]}; alone: {line[1]}")

    def quit(self):
        """The operator page's Q, Q: the kiosk stays stopped until `systemctl start`."""
        since = self.guest_time()
        # Held two seconds: the kiosk reads its keys once a frame, and under TCG a frame takes
        # about half a second.
        self.vm.qmp.keys("ctrl", "alt", "o", hold=2.0)
        self.wait("'operator: page open' in journalctl -u mallet",
                  lambda: self.journal(since, grep="^operator: page open").strip(), 120)
        time.sleep(8)
        self.screen("vm-operator")
        # Q asks first ("Q again quits the kiosk"), a second Q within 5 s quits: two presses,
        # each held over a frame, a second apart.
        self.vm.qmp.keys("q", hold=1.0)
        time.sleep(1.0)
        self.vm.qmp.keys("q", hold=1.0)
        self.wait("mallet.service inactive after Q, Q",
                  lambda: self.unit()["ActiveState"] in ("inactive", "failed") and True, 180)
        time.sleep(15)
        u = self.unit()
        session = self.unit("mallet-session")
        if u["ActiveState"] != "inactive":
            raise VmError(f"after Q the kiosk is {u['ActiveState']} (expected to stay inactive)")
        if session["ActiveState"] not in ("inactive", "deactivating"):
            raise VmError(f"after Q its display is {session['ActiveState']}")
        self.out("systemctl start mallet", timeout=300)
        self.wait_active(600)
        asked = self.journal(since, grep="^operator: Q asks first").strip()
        if not asked:
            raise VmError("the first Q did not ask first ('operator: Q asks first' not in the journal)")
        return "asked on Q, stopped on the second Q and stayed stopped 15 s; display stopped with it; started again"

    def update(self):
        """A newer build installed with apt over the running kiosk keeps the operator's
        edits, the calibration and the counters, and the kiosk comes back by itself."""
        newer = self.out("ls /opt/mallet-test/newer/mallet_*.deb")
        self.out("echo '# edited by the operator' >> /etc/mallet/mallet.toml")
        state_before = self.out("ls /var/lib/mallet | sort")
        old = self.unit()["MainPID"]
        code, log = self.sh(f"DEBIAN_FRONTEND=noninteractive apt-get install -y "
                            f"-o Dpkg::Options::=--force-confdef -o Dpkg::Options::=--force-confold {newer}", timeout=900)
        if code != 0:
            raise VmError(f"apt-get install of the newer package failed: {log[-400:]}")
        u, waited = self.wait_active(600, not_pid=old)
        problems = []
        if "# edited by the operator" not in self.out("tail -n 2 /etc/mallet/mallet.toml"):
            problems.append("the operator's edit of /etc/mallet/mallet.toml is gone")
        state_after = self.out("ls /var/lib/mallet | sort")
        missing = set(state_before.split()) - set(state_after.split())
        if missing:
            problems.append(f"/var/lib/mallet lost {sorted(missing)}")
        version = self.out("dpkg-query -W -f '${Version}' mallet")
        if problems:
            raise VmError("; ".join(problems))
        return f"now {version}, kiosk back as {u['MainPID']} after {waited:.0f} s; state kept: {state_after.split()}"

    def reboot(self):
        """A reboot brings the kiosk back by itself."""
        self.vm.agent.shutdown("reboot")
        time.sleep(10)
        start = time.monotonic()
        if not self.vm.agent.connect(900):
            raise VmError("the guest agent did not come back after the reboot")
        u, _ = self.wait_active(900)
        seconds = time.monotonic() - start
        self.timings.append(("reboot → mallet.service active", seconds))
        return f"back as {u['MainPID']} {seconds:.0f} s after the reboot"

    # --- running ----------------------------------------------------------------------------
    def run(self, names):
        if self.args.attach:
            self.vm.attach()
        else:
            self.vm.start()
        failed = 0
        self.ran = 0
        try:
            for name in names:
                self.ran += 1
                start = time.monotonic()
                since = self.guest_time() if name != "first-boot" else None
                try:
                    said = getattr(self, name.replace("-", "_"))()
                    print(f"ok   {name} ({time.monotonic() - start:.0f} s): {said}", flush=True)
                except VmError as e:
                    failed += 1
                    print(f"FAIL {name} ({time.monotonic() - start:.0f} s): {e}", flush=True)
                    if since:
                        self.failure_journal(name, since)
                    if name == "first-boot":
                        break
        finally:
            # The guest's journal of this boot, for whoever reads a failure afterwards.
            try:
                _, text = self.sh("journalctl -b -o short-monotonic --no-pager", timeout=300)
                with open(os.path.join(self.args.out, "journal.txt"), "w") as f:
                    f.write(text)
            except Exception as e:  # the machine may be the reason the run failed
                print(f"system: could not save the guest's journal: {e}")
            if not self.args.attach:
                self.vm.stop()
        print("timings:")
        for what, seconds in self.timings:
            print(f"  {seconds:7.1f} s  {what}")
        return failed


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--image", required=True, help="folder with disk.raw, vmlinuz, initrd.img")
    parser.add_argument("--out", required=True, help="folder for the logs, screens and the WAV")
    parser.add_argument("--only", default="", help="comma-separated scenarios (first-boot always runs)")
    parser.add_argument("--accel", default="tcg", choices=["tcg", "kvm"])
    parser.add_argument("--suite", choices=["bookworm", "trixie"],
                        help="the image's Debian release (first-boot checks the guest's)")
    parser.add_argument("--reference", help="first boot's screen signature (JSON); written when missing")
    parser.add_argument("--screens", help="also write the screens (PNG) here")
    parser.add_argument("--attach", action="store_true", help="drive the machine already running (its sockets in --out)")
    args = parser.parse_args()
    names = SCENARIOS
    if args.only:
        wanted = args.only.split(",")
        unknown = [w for w in wanted if w not in SCENARIOS]
        if unknown:
            parser.error(f"unknown scenario(s) {unknown}; known: {', '.join(SCENARIOS)}")
        names = ["first-boot"] + [n for n in SCENARIOS if n in wanted and n != "first-boot"]
    os.makedirs(args.out, exist_ok=True)
    test = Test(args)
    failed = test.run(names)
    skipped = len(names) - test.ran
    print(f"system: {test.ran - failed} passed, {failed} failed" + (f", {skipped} not run" if skipped else ""))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())

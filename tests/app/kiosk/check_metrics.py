#!/usr/bin/python3
"""Checks a kiosk run's metrics file against its log, with an independent parser.

usage: check_metrics.py METRICS_FILE LOG

LOG: a headless run's log.txt, or a window kiosk's stderr (journald priority prefixes).
The file must parse with prometheus_client's own parser (Debian's python3-prometheus-client),
hold every family the kiosk promises with its type, and count what the log says: the strikes
summed over their labels equal the log's strike lines, and mallet_frames_total equals the
frames of its last line ("ran ... N frames, M strikes" headless; "stopping after N frames
and M strikes" in a window). Prints what it compared; exits 1 on the first difference.
"""
import re
import sys

from prometheus_client.parser import text_string_to_metric_families

# prometheus_client names a counter's family without its _total suffix.
EXPECTED = {
    "mallet_strikes": "counter",
    "mallet_visitor_sessions": "counter",
    "mallet_visitor_session_seconds": "histogram",
    "mallet_frames": "counter",
    "mallet_frame_seconds": "histogram",
    "mallet_audio_xruns": "counter",
    "mallet_audio_output_latency_seconds": "gauge",
    "mallet_remote_connected": "gauge",
    "mallet_remote_battery_ratio": "gauge",
    "mallet_tracking_lost_seconds": "counter",
    "mallet_settings_refused": "gauge",
    "mallet_state_folder_writable": "gauge",
    "mallet_state": "gauge",
    "mallet_uptime_seconds": "gauge",
    "mallet_restarts": "counter",
    "mallet_build_info": "gauge",
}


def fail(message):
    print("check_metrics: " + message)
    sys.exit(1)


def main():
    metrics_file, log_file = sys.argv[1], sys.argv[2]
    with open(metrics_file, encoding="utf-8") as f:
        text = f.read()
    try:
        families = {f.name: f for f in text_string_to_metric_families(text)}
    except Exception as e:  # the parser's own words are the point of this check
        fail("%s does not parse: %s" % (metrics_file, e))
    for name, kind in EXPECTED.items():
        if name not in families:
            fail("no family %s (found: %s)" % (name, ", ".join(sorted(families))))
        if families[name].type != kind:
            fail("%s is a %s, expected a %s" % (name, families[name].type, kind))

    def samples(family, sample_name):
        return [s for s in families[family].samples if s.name == sample_name]

    strikes = samples("mallet_strikes", "mallet_strikes_total")
    strikes_total = sum(s.value for s in strikes)
    by_label = {(s.labels["instrument"], s.labels["material"]): s.value for s in strikes}
    frames_total = samples("mallet_frames", "mallet_frames_total")[0].value
    frame_count = samples("mallet_frame_seconds", "mallet_frame_seconds_count")[0].value
    inf_bucket = [s.value for s in samples("mallet_frame_seconds", "mallet_frame_seconds_bucket")
                  if s.labels["le"] == "+Inf"]
    states = {s.labels["state"]: s.value for s in samples("mallet_state", "mallet_state")}

    with open(log_file, encoding="utf-8") as f:
        log = f.read().splitlines()
    log = [re.sub(r"^<\d>", "", line) for line in log]  # the window kiosk's priorities
    log_strikes = sum(1 for line in log if line.startswith("strike "))
    log_by_label = {}
    for line in log:
        m = re.match(r"strike t=\S+ bar=\d+ (\S+) note=.* material=(\S+)$", line)
        if m:
            log_by_label[m.groups()] = log_by_label.get(m.groups(), 0) + 1
    ran = [re.search(r"^(?:ran [0-9.]+ s: (\d+) frames, (\d+) strikes"
                     r"|mallet run: stopping after (\d+) frames and (\d+) strikes)", line) for line in log]
    ran = [[g for g in m.groups() if g is not None] for m in ran if m]
    if len(ran) != 1:
        fail("%s has no single \"ran ... N frames\" or \"stopping after N frames\" line" % log_file)
    log_frames, log_ran_strikes = int(ran[0][0]), int(ran[0][1])

    print("metrics: %d families; strikes %d over %s; frames %d (histogram count %d); states %s"
          % (len(families), strikes_total, by_label, frames_total, frame_count, states))
    print("log: %d strike lines %s; last line: %d frames, %d strikes"
          % (log_strikes, log_by_label, log_frames, log_ran_strikes))
    if strikes_total != log_strikes or strikes_total != log_ran_strikes:
        fail("mallet_strikes_total sums to %d, the log has %d strike lines and says %d strikes"
             % (strikes_total, log_strikes, log_ran_strikes))
    for labels, n in log_by_label.items():
        if by_label.get(labels) != n:
            fail("mallet_strikes_total%s = %s, the log has %d" % (labels, by_label.get(labels), n))
    if frames_total != log_frames:
        fail("mallet_frames_total = %d, the log says %d frames" % (frames_total, log_frames))
    if frame_count != frames_total or inf_bucket != [frames_total]:
        fail("mallet_frame_seconds counts %d (+Inf %s), frames %d" % (frame_count, inf_bucket, frames_total))
    if sorted(states) != ["attract", "calibration", "operator", "play"] or sum(states.values()) != 1:
        fail("mallet_state: expected one series per state, exactly one at 1: %s" % states)
    print("check_metrics: ok")


if __name__ == "__main__":
    main()

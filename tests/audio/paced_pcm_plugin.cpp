// A sound card for tests, as an ALSA external PCM (ioplug; no kernel driver, no /dev/snd):
// it plays nothing, but takes frames at its sample rate by the monotonic clock, as a card's
// DMA pointer does, and reports an underrun when that pointer reaches what the application
// has written. So PortAudio's real ALSA path — poll, avail_update, the xrun handler's
// snd_pcm_status, snd_pcm_prepare and restart — runs as on a card. ALSA's null and file
// plugins take any amount at once and never underrun.
//
// Arguments: `stall_ms` and `every_ms` make the card lose stall_ms of time every every_ms of
// playback (counted from each start), all at once: a guest descheduled by its host (the
// QEMU VM where the kiosk aborted) or a machine too busy to run the audio thread. A buffer
// shorter than stall_ms then underruns at every stall, a longer one rides it out.
// `buffer_bytes` (optional) fixes the buffer at that size whatever the application asks, as a
// driver may, and as a JACK server keeps its own period.
//
//   pcm_type.mallet_paced { lib "/path/to/libasound_module_pcm_mallet_paced.so" }
//   pcm.paced { type mallet_paced stall_ms 30 every_ms 60 }
//   pcm.!default { type plug slave { pcm "paced" format S16_LE } }
//
// Playback only; interleaved S16_LE or FLOAT_LE, any channel count up to 8 and rate.
#include <alsa/asoundlib.h>
#include <alsa/pcm_external.h>
#include <poll.h>
#include <sys/timerfd.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <ctime>

namespace {

struct Paced {
  snd_pcm_ioplug_t io{};
  int timer_fd = -1;
  std::int64_t stall_ns = 0;
  std::int64_t every_ns = 0;
  std::int64_t start_ns = 0;
  bool running = false;
  snd_pcm_sframes_t last = 0;  // the pointer last reported (within the buffer)
};

Paced& of(snd_pcm_ioplug_t* io) { return *static_cast<Paced*>(io->private_data); }

std::int64_t now_ns() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return std::int64_t{ts.tv_sec} * 1'000'000'000 + ts.tv_nsec;
}

// Frames the card has taken since the start: its clock, plus the time lost to stalls.
std::int64_t taken(const Paced& p) {
  const std::int64_t elapsed = now_ns() - p.start_ns;
  const std::int64_t lost = p.every_ns > 0 ? elapsed / p.every_ns * p.stall_ns : 0;
  return (elapsed + lost) / 1000 * static_cast<std::int64_t>(p.io.rate) / 1'000'000;
}

int arm(Paced& p, bool on) {
  itimerspec t{};
  if (on) {
    // Four ticks per period: a card interrupts at each period boundary of its own pointer,
    // which the stalls shift against this clock; a quarter period keeps the wake-up close to
    // the moment a period is free, as on a card.
    const std::int64_t ns = static_cast<std::int64_t>(p.io.period_size) * 250'000'000 / p.io.rate;
    t.it_value.tv_sec = t.it_interval.tv_sec = static_cast<time_t>(ns / 1'000'000'000);
    t.it_value.tv_nsec = t.it_interval.tv_nsec = static_cast<long>(ns % 1'000'000'000);
  }
  return timerfd_settime(p.timer_fd, 0, &t, nullptr) < 0 ? -errno : 0;
}

int start(snd_pcm_ioplug_t* io) {
  Paced& p = of(io);
  p.start_ns = now_ns();
  p.running = true;
  p.last = 0;
  return arm(p, true);
}

int stop(snd_pcm_ioplug_t* io) {
  Paced& p = of(io);
  p.running = false;
  return arm(p, false);
}

snd_pcm_sframes_t pointer(snd_pcm_ioplug_t* io) {
  Paced& p = of(io);
  if (!p.running) return p.last;
  const std::int64_t pos = taken(p);
  // appl_ptr counts from 0 at prepare, as `taken` does from the start: the card has played
  // everything written, so it underruns. (Between two updates the pointer moves less than a
  // buffer unless this happens, so a position within the buffer is enough for ioplug.)
  if (pos >= static_cast<std::int64_t>(io->appl_ptr)) return -EPIPE;
  p.last = static_cast<snd_pcm_sframes_t>(pos % static_cast<std::int64_t>(io->buffer_size));
  return p.last;
}

snd_pcm_sframes_t transfer(snd_pcm_ioplug_t*, const snd_pcm_channel_area_t*, snd_pcm_uframes_t,
                           snd_pcm_uframes_t size) {
  return static_cast<snd_pcm_sframes_t>(size);  // played into the air
}

int prepare(snd_pcm_ioplug_t* io) {
  Paced& p = of(io);
  p.running = false;
  p.last = 0;
  return arm(p, false);
}

int poll_count(snd_pcm_ioplug_t*) { return 1; }

int poll_fds(snd_pcm_ioplug_t* io, pollfd* pfd, unsigned int space) {
  if (space < 1) return 0;
  pfd->fd = of(io).timer_fd;
  pfd->events = POLLIN;
  pfd->revents = 0;
  return 1;
}

int poll_revents(snd_pcm_ioplug_t* io, pollfd* pfd, unsigned int nfds, unsigned short* revents) {
  if (nfds >= 1 && (pfd->revents & POLLIN)) {
    std::uint64_t ticks = 0;
    while (read(of(io).timer_fd, &ticks, sizeof ticks) > 0) {
    }
  }
  const snd_pcm_sframes_t avail = snd_pcm_avail_update(io->pcm);
  if (avail < 0)
    *revents = POLLERR;
  else
    *revents = static_cast<snd_pcm_uframes_t>(avail) >= io->period_size ? POLLOUT : 0;
  return 0;
}

int close_pcm(snd_pcm_ioplug_t* io) {
  Paced* p = &of(io);
  if (p->timer_fd >= 0) close(p->timer_fd);
  delete p;
  return 0;
}

snd_pcm_ioplug_callback_t callbacks() {
  snd_pcm_ioplug_callback_t c{};
  c.start = start;
  c.stop = stop;
  c.pointer = pointer;
  c.transfer = transfer;
  c.close = close_pcm;
  c.prepare = prepare;
  c.poll_descriptors_count = poll_count;
  c.poll_descriptors = poll_fds;
  c.poll_revents = poll_revents;
  return c;
}
const snd_pcm_ioplug_callback_t kCallbacks = callbacks();

int constrain(snd_pcm_ioplug_t* io, long buffer_bytes) {
  static const unsigned int access[] = {SND_PCM_ACCESS_MMAP_INTERLEAVED, SND_PCM_ACCESS_RW_INTERLEAVED};
  static const unsigned int formats[] = {SND_PCM_FORMAT_S16_LE, SND_PCM_FORMAT_FLOAT_LE};
  int err = 0;
  if ((err = snd_pcm_ioplug_set_param_list(io, SND_PCM_IOPLUG_HW_ACCESS, 2, access)) < 0) return err;
  if ((err = snd_pcm_ioplug_set_param_list(io, SND_PCM_IOPLUG_HW_FORMAT, 2, formats)) < 0) return err;
  if ((err = snd_pcm_ioplug_set_param_minmax(io, SND_PCM_IOPLUG_HW_CHANNELS, 1, 8)) < 0) return err;
  if ((err = snd_pcm_ioplug_set_param_minmax(io, SND_PCM_IOPLUG_HW_RATE, 8000, 192000)) < 0) return err;
  if (buffer_bytes > 0) {
    const auto fixed = static_cast<unsigned int>(buffer_bytes);
    if ((err = snd_pcm_ioplug_set_param_minmax(io, SND_PCM_IOPLUG_HW_PERIOD_BYTES, 64, fixed / 2)) < 0) return err;
    if ((err = snd_pcm_ioplug_set_param_minmax(io, SND_PCM_IOPLUG_HW_PERIODS, 2, 1024)) < 0) return err;
    return snd_pcm_ioplug_set_param_minmax(io, SND_PCM_IOPLUG_HW_BUFFER_BYTES, fixed, fixed);
  }
  if ((err = snd_pcm_ioplug_set_param_minmax(io, SND_PCM_IOPLUG_HW_PERIOD_BYTES, 64, 1 << 20)) < 0) return err;
  if ((err = snd_pcm_ioplug_set_param_minmax(io, SND_PCM_IOPLUG_HW_PERIODS, 2, 1024)) < 0) return err;
  return snd_pcm_ioplug_set_param_minmax(io, SND_PCM_IOPLUG_HW_BUFFER_BYTES, 128, 1 << 22);
}

}  // namespace

extern "C" {

int _snd_pcm_mallet_paced_open(snd_pcm_t** pcmp, const char* name, snd_config_t*, snd_config_t* conf,
                               snd_pcm_stream_t stream, int mode) {
  if (stream != SND_PCM_STREAM_PLAYBACK) return -EINVAL;
  long stall_ms = 0, every_ms = 0, buffer_bytes = 0;
  snd_config_iterator_t i, next;
  snd_config_for_each(i, next, conf) {
    snd_config_t* n = snd_config_iterator_entry(i);
    const char* id = nullptr;
    if (snd_config_get_id(n, &id) < 0) continue;
    if (!std::strcmp(id, "comment") || !std::strcmp(id, "type") || !std::strcmp(id, "hint")) continue;
    long* value = !std::strcmp(id, "stall_ms")       ? &stall_ms
                  : !std::strcmp(id, "every_ms")     ? &every_ms
                  : !std::strcmp(id, "buffer_bytes") ? &buffer_bytes
                                                     : nullptr;
    if (!value || snd_config_get_integer(n, value) < 0 || *value < 0) {
      SNDERR("mallet_paced: bad or unknown argument %s", id);
      return -EINVAL;
    }
  }
  auto* p = new Paced;
  p->stall_ns = stall_ms * 1'000'000;
  p->every_ns = every_ms * 1'000'000;
  p->timer_fd = timerfd_create(CLOCK_MONOTONIC, TFD_NONBLOCK | TFD_CLOEXEC);
  if (p->timer_fd < 0) {
    const int err = -errno;
    delete p;
    return err;
  }
  p->io.version = SND_PCM_IOPLUG_VERSION;
  p->io.name = "Mallet paced test card";
  p->io.flags = SND_PCM_IOPLUG_FLAG_MONOTONIC;
  p->io.poll_fd = p->timer_fd;
  p->io.poll_events = POLLIN;
  p->io.mmap_rw = 0;
  p->io.callback = &kCallbacks;
  p->io.private_data = p;
  int err = snd_pcm_ioplug_create(&p->io, name, stream, mode);
  if (err < 0) {
    close(p->timer_fd);
    delete p;
    return err;
  }
  if ((err = constrain(&p->io, buffer_bytes)) < 0) {
    snd_pcm_ioplug_delete(&p->io);  // calls close_pcm
    return err;
  }
  *pcmp = p->io.pcm;
  return 0;
}

SND_PCM_PLUGIN_SYMBOL(mallet_paced)

}  // extern "C"

#pragma once
// libjpeg's error handling made safe for a program that must not exit on a bad frame:
// libjpeg's default handler calls exit(); this one jumps back to the caller's setjmp with
// the message kept, and treats a warning (corrupt data that libjpeg would paper over with
// grey) the same way. Internal to frame_decode and led_frame_synth.
//
// Use: JpegError err; cinfo.err = jpeg_error_init(err); if (setjmp(err.jump)) {destroy;
// fail}. No C++ object with a destructor may be created between the setjmp and the end of
// the libjpeg calls it guards (the jump would skip its destructor).
#include <csetjmp>
#include <cstdio>  // jpeglib.h needs FILE declared first

#include <jpeglib.h>

namespace mallet::input::camera {

struct JpegError {
  jpeg_error_mgr mgr;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX];
};

//! libjpeg's error_exit: keep the message, jump back.
[[noreturn]] inline void jpeg_error_jump(j_common_ptr cinfo) {
  auto* err = reinterpret_cast<JpegError*>(cinfo->err);
  (*cinfo->err->format_message)(cinfo, err->message);
  std::longjmp(err->jump, 1);
}

//! libjpeg's emit_message: a warning (level < 0) is an error; trace messages are dropped.
inline void jpeg_error_on_warning(j_common_ptr cinfo, int msg_level) {
  if (msg_level < 0) jpeg_error_jump(cinfo);
}

//! libjpeg's output_message: nothing is printed (the caller reports the message).
inline void jpeg_error_silent(j_common_ptr) {}

//! `err` set up as the handlers above; the value for cinfo.err.
inline jpeg_error_mgr* jpeg_error_init(JpegError& err) {
  jpeg_error_mgr* mgr = jpeg_std_error(&err.mgr);
  mgr->error_exit = jpeg_error_jump;
  mgr->emit_message = jpeg_error_on_warning;
  mgr->output_message = jpeg_error_silent;
  err.message[0] = '\0';
  return mgr;
}

}  // namespace mallet::input::camera

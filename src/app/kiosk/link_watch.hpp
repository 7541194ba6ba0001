#pragma once
// The IR tracker's link (the Wii Remote or the V4L2 camera) as the kiosk's main loop sees
// it. The reading thread may lose the link and have it back between two of the loop's looks
// (a frame that takes longer than the camera's reopening, on a loaded machine): the loss is
// then still said, with its reason, and the kiosk's states hear it, as if it had been seen.
#include <cstdint>
#include <string>
#include <vector>

namespace mallet::app {

//! The IR tracker's link at one look (input_choice's ir_link): the kiosk's states, log and
//! metrics treat the remote and the camera alike.
struct IrLink {
  bool present = false;   //!< the stage has a remote or a camera
  bool up = false;        //!< it runs (the remote's IR start-up done; the camera streams)
  std::string identity;   //!< "Wii Remote 00:1f:…" / "camera USB Camera (usb-…)": the calibration's owner
  std::string problem;    //!< why it is not up
  std::uint64_t drops = 0;  //!< times the link dropped since its thread started
  std::string last_drop;    //!< why it last dropped (kept once it is up again)
};

//! One change to tell: the link lost (and why) or connected.
struct LinkChange {
  bool connected = false;
  std::string why;  //!< a loss's reason
};

class LinkWatch {
 public:
  //! The changes since the last look, in order: none, one, or a loss and the connection
  //! back when the link dropped and returned between the two looks.
  std::vector<LinkChange> look(const IrLink& link);
  //! Up at the last look.
  bool up() const { return up_; }

 private:
  bool up_ = false;
  std::uint64_t drops_ = 0;
};

}  // namespace mallet::app

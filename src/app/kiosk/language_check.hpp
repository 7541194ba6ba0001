#pragma once
// `mallet doctor`'s language check: every language the settings show ([kiosk] language,
// [attract] languages) has a translation of every text (the shipped template, mallet.pot)
// and a font for every letter of them. It names the texts and the letters it finds missing.
#include <filesystem>

#include "core/app_config.hpp"
#include "core/doctor_check.hpp"

namespace mallet::app {

//! The template of every text the kiosk shows: <data>/po/mallet.pot.
std::filesystem::path text_template();

DoctorCheck check_language(const AppConfig& config);

}  // namespace mallet::app

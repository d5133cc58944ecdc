// trispline::ui dialogs — small modal windows: About, Keys and mouse (the key list), the crash-recovery
// prompt shown at start when a previous session did not end cleanly, and "Save changes?" before Quit/New/Open.
#pragma once

#include <cstddef>
#include <string>

namespace trispline::ui {

// Non-modal help windows; `open` is cleared when the user closes them.
void draw_about_window(bool* open, const std::string& gl_renderer);
void draw_keys_window(bool* open);

enum class RecoverChoice { Pending, Recover, Discard };

// Modal "Recover unfinished session? (N commands)". Call every frame while the question is open.
RecoverChoice draw_recover_prompt(std::size_t command_count, const std::string& log_path);

enum class QuitChoice { Pending, SaveAndQuit, Quit, Cancel };

// Modal "Save changes to DOC before <doing>?" for a modified document (doing: "quitting", "starting a new scene",
// "opening another log"). SaveAndQuit = save, then go on; Quit = "Don't save": go on and drop the changes.
QuitChoice draw_quit_prompt(const std::string& document, const char* doing = "quitting");

}  // namespace trispline::ui

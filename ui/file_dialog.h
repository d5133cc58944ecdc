// trispline::ui::FileDialog — a small modal file chooser (no native dialogs: GLFW has none): a path field, the
// folders and matching files of the current folder, ".." to go up. Used for Load… (meshes, volumes: a DICOM folder
// too), Open… and Save As… (command logs), the Volume panel's and Tile Paint's exports. A Save dialog with one
// extension returns the name with it added, and asks before replacing a file: the first Save of an existing name
// says so, a second Save of the same name replaces it (as a desktop Save dialog's "Replace?").
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace trispline::ui {

class FileDialog {
 public:
  enum class Mode { Open, Save };

  // Opens the dialog on the next draw(). extensions: lower-case with the dot (".obj", ".nii.gz": a file matches when
  // its name ends with one, any case); empty = all files.
  void open(std::string title, Mode mode, std::vector<std::string> extensions,
            const std::filesystem::path& start_folder = {});
  // An import option shown as a checkbox above the buttons until the next open() (Blender's file browser keeps an
  // importer's options beside the file list); `value` is its state, kept across dialogs. Empty label = none.
  void set_option(std::string label, std::string tooltip, bool value);
  bool option() const { return option_value_; }
  // Open: a button beside Open that chooses the folder listed (a DICOM series is a folder), with `tooltip`; until the
  // next open(). Empty label = none.
  void set_folder_choice(std::string label, std::string tooltip);
  // Save: the file name the name field starts with (until the next open()).
  void set_name(std::string name) { name_ = std::move(name); }
  // Draws the modal if open; returns the chosen path once (absolute, lexically normal).
  std::optional<std::filesystem::path> draw();
  bool is_open() const { return open_ || visible_; }

 private:
  void list_folder();
  bool matches(const std::filesystem::path& p) const;
  std::filesystem::path save_target() const;  // Save: the folder typed in the path field / the name field
  // Enters `dir`: lists it and shows it in the path field (Open: which takes the keyboard again).
  void enter_folder(const std::filesystem::path& dir);
  // "Up" and the path field, then the last error; sets go_to on Up; true when Enter was pressed in the field.
  bool draw_path_row(std::optional<std::filesystem::path>& go_to);
  // The folders and files of folder_, leaving `footer` pixels below: a clicked folder in go_to, a clicked file in
  // the path (and name) field; a double click sets accept.
  void draw_listing(float footer, std::optional<std::filesystem::path>& go_to, bool& accept);
  bool draw_name_field();  // Save: the name field; true when Enter was pressed in it
  void draw_option();      // the option checkbox and its tooltip
  // The folder, Open / Save and Cancel buttons, right-aligned (buttons_w: their width, pixels): the folder button
  // sets chosen; Open / Save and Enter outside a field set accept (Open) or accept_name (Save); Cancel and Escape
  // close the dialog.
  void draw_buttons(float buttons_w, std::optional<std::filesystem::path>& chosen, bool& accept, bool& accept_name);
  // The path accepted from the path field (or, accept_name, from the name field): a folder is entered; a missing
  // file (Open) or folder (Save), or no name (Save), sets error_; so does an existing file (Save) the first time it
  // is accepted; else it is chosen and the dialog closes.
  void accept_typed(bool accept_name, std::optional<std::filesystem::path>& chosen);

  std::string title_;
  Mode mode_ = Mode::Open;
  std::vector<std::string> extensions_;
  std::filesystem::path folder_;
  std::string path_text_;  // editable full path
  std::string name_;       // Save: file name in folder_
  std::vector<std::filesystem::path> dirs_, files_;
  std::string error_;
  std::filesystem::path replace_;  // Save: the existing file the user was asked about (a second Save replaces it)
  bool open_ = false;              // open() called, popup not yet opened
  bool visible_ = false;           // popup showing
  bool refocus_ = false;           // Open: give the path field the keyboard on the next draw (a folder was entered)
  std::string option_label_, option_tooltip_;
  std::string folder_label_, folder_tooltip_;
  bool option_value_ = false;
};

}  // namespace trispline::ui

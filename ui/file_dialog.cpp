#include "ui/file_dialog.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cctype>
#include <utility>

#include "core/base/text.h"
#include "ui/gui_probe.h"
#include "ui/imgui_host.h"
#include "ui/theme.h"

namespace fs = std::filesystem;

namespace trispline::ui {

namespace {

// The path and name fields: Enter accepts, and a field that gets the keyboard selects its whole text (typing
// replaces it).
constexpr ImGuiInputTextFlags kFileDialogField =
    ImGuiInputTextFlags_EnterReturnsTrue | ImGuiInputTextFlags_AutoSelectAll;

// The buttons row below the listing: the extension filter ("*.obj *.ply"), the buttons' width and whether the filter
// takes a line of its own (a long filter must not push Open past the dialog's edge); height: what the rows under the
// listing take. Pixels.
struct FileDialogFooter {
  std::string filter;
  float buttons_w = 0.0f;
  bool filter_own_line = false;
  float height = 0.0f;
};

// The footer's geometry in the current window: folder_label names the folder button (empty: none), option_label
// the option checkbox (empty: none); save: the Save dialog's name row.
FileDialogFooter file_dialog_footer(const std::vector<std::string>& extensions, const std::string& folder_label,
                                    const std::string& option_label, bool save) {
  FileDialogFooter f;
  for (const std::string& e : extensions) f.filter += (f.filter.empty() ? "" : " ") + std::string("*") + e;
  const ImGuiStyle& style = ImGui::GetStyle();
  const float folder_w =
      folder_label.empty() ? 0.0f : ImGui::CalcTextSize(folder_label.c_str()).x + 2 * style.FramePadding.x;
  f.buttons_w = 2 * 80.0f + style.ItemSpacing.x + (folder_w > 0 ? folder_w + style.ItemSpacing.x : 0.0f);
  const float row_w = ImGui::GetContentRegionAvail().x;
  f.filter_own_line =
      !f.filter.empty() && ImGui::CalcTextSize(f.filter.c_str()).x + style.ItemSpacing.x + f.buttons_w > row_w;
  f.height = ImGui::GetFrameHeightWithSpacing() *
             ((save ? 2.6f : 1.6f) + (option_label.empty() ? 0 : 1) + (f.filter_own_line ? 1 : 0));
  return f;
}

// The extension filter at the buttons row's left, or on a line of its own above it.
void draw_file_filter(const FileDialogFooter& f) {
  if (f.filter.empty()) return;
  ImGui::PushTextWrapPos(0.0f);
  ImGui::TextColored(colors::dim, "%s", f.filter.c_str());
  ImGui::PopTextWrapPos();
  if (!f.filter_own_line) ImGui::SameLine();
}
}  // namespace

void FileDialog::open(std::string title, Mode mode, std::vector<std::string> extensions, const fs::path& start_folder) {
  title_ = std::move(title);
  mode_ = mode;
  extensions_ = std::move(extensions);
  std::error_code ec;
  folder_ = start_folder.empty() ? fs::current_path(ec) : fs::absolute(start_folder, ec);
  if (!fs::is_directory(folder_, ec)) folder_ = fs::current_path(ec);
  path_text_ = (folder_ / "").string();
  list_folder();
  open_ = true;
  option_label_.clear();
  folder_label_.clear();
  name_.clear();  // Save: set_name() after open() gives the name; never the last dialog's
  replace_.clear();
  error_.clear();
}

void FileDialog::set_folder_choice(std::string label, std::string tooltip) {
  folder_label_ = std::move(label);
  folder_tooltip_ = std::move(tooltip);
}

void FileDialog::set_option(std::string label, std::string tooltip, bool value) {
  option_label_ = std::move(label);
  option_tooltip_ = std::move(tooltip);
  option_value_ = value;
}

bool FileDialog::matches(const fs::path& p) const {
  if (extensions_.empty()) return true;
  const std::string name = core::ascii_lower(p.filename().string());
  return std::any_of(extensions_.begin(), extensions_.end(), [&](const std::string& e) { return name.ends_with(e); });
}

void FileDialog::list_folder() {
  dirs_.clear();
  files_.clear();
  error_.clear();
  std::error_code ec;
  for (fs::directory_iterator it(folder_, fs::directory_options::skip_permission_denied, ec), end; !ec && it != end;
       it.increment(ec)) {
    const fs::path& p = it->path();
    if (p.filename().string().starts_with(".")) continue;
    std::error_code ec2;
    if (it->is_directory(ec2))
      dirs_.push_back(p);
    else if (matches(p))
      files_.push_back(p);
  }
  if (ec) error_ = "cannot list " + folder_.string() + ": " + ec.message();
  std::sort(dirs_.begin(), dirs_.end());
  std::sort(files_.begin(), files_.end());
}

fs::path FileDialog::save_target() const {
  // The path field names the folder (ending in a separator, or an existing folder) or the whole file; the name
  // field names the file in that folder. What is typed there wins over the folder listed, so a mistyped folder is
  // refused rather than replaced by the listed one.
  std::error_code ec;
  const fs::path typed(path_text_);
  const bool names_folder = path_text_.empty() || path_text_.back() == '/' || fs::is_directory(typed, ec);
  const fs::path folder = path_text_.empty() ? folder_ : names_folder ? typed : typed.parent_path();
  if (!name_.empty()) return folder / name_;
  return names_folder ? folder / "" : typed;
}

void FileDialog::enter_folder(const fs::path& dir) {
  folder_ = dir.lexically_normal();
  path_text_ = (folder_ / "").string();
  list_folder();
  refocus_ = mode_ == Mode::Open;  // the path field takes the keyboard again, its text selected
}

bool FileDialog::draw_path_row(std::optional<fs::path>& go_to) {
  if (ImGui::Button("Up")) go_to = folder_.parent_path();
  ImGui::SameLine();
  ImGui::SetNextItemWidth(-1);
  // Open: the path field takes the keyboard at once; Save: the name field below does. Either way a field that gets
  // the keyboard selects its whole text, so typing replaces it (Ctrl+A selects it again).
  if (mode_ == Mode::Open && (ImGui::IsWindowAppearing() || std::exchange(refocus_, false)))
    ImGui::SetKeyboardFocusHere();
  const bool accept = ImGui::InputText("##path", &path_text_, kFileDialogField);
  probe::item("file.path");
  probe::value("file.path", path_text_);
  if (!error_.empty()) ImGui::TextColored(colors::error, "%s", error_.c_str());
  probe::value("file.error", error_);
  return accept;
}

void FileDialog::draw_listing(float footer, std::optional<fs::path>& go_to, bool& accept) {
  ImGui::BeginChild("##listing", ImVec2(0, -footer), true);
  for (const fs::path& d : dirs_) {
    const std::string label = d.filename().string() + "/";
    if (ImGui::Selectable(label.c_str(), false, ImGuiSelectableFlags_DontClosePopups)) go_to = d;
    probe::item("file.entry." + label);
  }
  for (const fs::path& f : files_) {
    const bool selected = path_text_ == f.string();
    if (ImGui::Selectable(f.filename().string().c_str(), selected,
                          ImGuiSelectableFlags_DontClosePopups | ImGuiSelectableFlags_AllowDoubleClick)) {
      path_text_ = f.string();
      name_ = f.filename().string();
      if (ImGui::IsMouseDoubleClicked(0) || ImGuiHost::click_count() >= 2) accept = true;
    }
    probe::item("file.entry." + f.filename().string());
  }
  ImGui::EndChild();
}

bool FileDialog::draw_name_field() {
  ImGui::AlignTextToFramePadding();
  ImGui::TextUnformatted("Name");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(-1);
  if (ImGui::IsWindowAppearing()) ImGui::SetKeyboardFocusHere();
  const bool accept_name = ImGui::InputText("##name", &name_, kFileDialogField);
  probe::item("file.name");
  probe::value("file.name", name_);
  return accept_name;
}

void FileDialog::draw_option() {
  ImGui::Checkbox(option_label_.c_str(), &option_value_);
  probe::item("file.option");
  probe::value("file.option", option_value_ ? "on" : "off");
  if (ImGui::IsItemHovered() && !option_tooltip_.empty()) {
    ImGui::BeginTooltip();
    ImGui::PushTextWrapPos(ImGui::GetFontSize() * 32.0f);  // a paragraph, not one screen-wide line
    ImGui::TextUnformatted(option_tooltip_.c_str());
    ImGui::PopTextWrapPos();
    ImGui::EndTooltip();
  }
}

void FileDialog::draw_buttons(float buttons_w, std::optional<fs::path>& chosen, bool& accept, bool& accept_name) {
  ImGui::SetCursorPosX(std::max(ImGui::GetCursorPosX(), ImGui::GetWindowContentRegionMax().x - buttons_w));
  if (!folder_label_.empty()) {
    if (ImGui::Button(folder_label_.c_str())) {
      chosen = folder_;
      ImGui::CloseCurrentPopup();
    }
    probe::item("file.folder");
    if (ImGui::IsItemHovered() && !folder_tooltip_.empty()) ImGui::SetTooltip("%s", folder_tooltip_.c_str());
    ImGui::SameLine();
  }
  if (ImGui::Button(mode_ == Mode::Open ? "Open" : "Save", ImVec2(80, 0)))
    (mode_ == Mode::Save ? accept_name : accept) = true;
  probe::item("file.ok");
  ImGui::SameLine();
  const bool cancel = ImGui::Button("Cancel", ImVec2(80, 0));
  probe::item("file.cancel");
  if (cancel || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape), false)) ImGui::CloseCurrentPopup();
  // Enter with no field typing (after a click on a file in the list): the entry shown in the path field, as Open.
  if (!ImGui::IsAnyItemActive() && (ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Enter), false) ||
                                    ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_KeyPadEnter), false)))
    (mode_ == Mode::Save ? accept_name : accept) = true;
}

void FileDialog::accept_typed(bool accept_name, std::optional<fs::path>& chosen) {
  std::error_code ec;
  fs::path p = fs::absolute(accept_name ? save_target() : fs::path(path_text_), ec).lexically_normal();
  if (!accept_name && fs::is_directory(p, ec)) {
    enter_folder(p);
  } else if (mode_ == Mode::Open && !fs::exists(p, ec)) {
    error_ = "no such file: " + p.string();
  } else if (mode_ == Mode::Save && !fs::is_directory(p.parent_path(), ec)) {
    error_ = "no such folder: " + p.parent_path().string() + " (nothing saved)";
  } else if (mode_ == Mode::Save && p.filename().empty()) {
    error_ = "type a file name";
  } else {
    if (mode_ == Mode::Save) {
      // The file the caller will write: the one extension a Save dialog offers added when the name lacks it.
      if (extensions_.size() == 1 && !core::has_extension(p, extensions_.front())) p += extensions_.front();
      if (fs::is_directory(p, ec)) {
        error_ = p.filename().string() + " is a folder (nothing saved)";
        return;
      }
      // An existing file is replaced only when Save is asked twice for it (the second time confirms).
      if (fs::exists(p, ec) && replace_ != p) {
        replace_ = p;
        error_ = p.filename().string() + " exists: Save again to replace it";
        return;
      }
    }
    chosen = p;
    ImGui::CloseCurrentPopup();
  }
}

std::optional<fs::path> FileDialog::draw() {
  std::optional<fs::path> chosen;
  if (open_) {
    ImGui::OpenPopup("###file_dialog");
    open_ = false;
  }
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowSize(ImVec2(std::min(640.0f, display.x * 0.9f), std::min(480.0f, display.y * 0.8f)),
                           ImGuiCond_Appearing);
  ImGui::SetNextWindowPos(ImVec2(display.x * 0.5f, display.y * 0.5f), ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  visible_ = ImGui::BeginPopupModal((title_ + "###file_dialog").c_str(), nullptr, ImGuiWindowFlags_NoSavedSettings);
  if (!visible_) return chosen;
  std::optional<fs::path> go_to;  // entered after the listing is drawn: enter_folder() rebuilds dirs_
  bool accept = draw_path_row(go_to);
  bool accept_name = false;

  const FileDialogFooter footer = file_dialog_footer(extensions_, folder_label_, option_label_, mode_ == Mode::Save);
  draw_listing(footer.height, go_to, accept);
  if (go_to) enter_folder(*go_to);

  if (mode_ == Mode::Save) accept_name = draw_name_field();
  if (!option_label_.empty()) draw_option();
  draw_file_filter(footer);
  draw_buttons(footer.buttons_w, chosen, accept, accept_name);
  const ImVec2 window_min = ImGui::GetWindowPos();
  probe::rect("file.dialog", window_min,
              ImVec2(window_min.x + ImGui::GetWindowSize().x, window_min.y + ImGui::GetWindowSize().y));

  if (accept || accept_name) accept_typed(accept_name, chosen);
  ImGui::EndPopup();
  return chosen;
}

}  // namespace trispline::ui

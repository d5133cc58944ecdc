// trispline::core::FileOutput — the trait of a command whose effect reaches outside the program's own state: it
// writes files (volume.export's SVG / glb / obj / ply) or asks its caller to (anim.record's frames, written by
// editor::Recorder). A command declares it by deriving from FileOutput as well as from Command.
//
// Opening a log, recovering a crashed session and moving through the History re-create the scene but never write
// such files again (docs/decisions.md, "Opening a log never writes files"): the replay calls set_writes_files(false)
// before the first redo, which then computes and keeps in the scene whatever the command keeps there (a volume's
// silhouettes) but writes nothing. Undo never touches a file, and a redo after an undo writes nothing either (the
// first redo's result is reused). Headless `trispline replay` leaves writing on: it writes under its --out folder.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/commands/command.h"
#include "core/params/command_context.h"

namespace trispline::core {

class FileOutput {
 public:
  virtual ~FileOutput() = default;
  // Whether the next redo writes the files (default: yes). Set before the first redo; later redos never write.
  void set_writes_files(bool on) { writes_files_ = on; }
  bool writes_files() const { return writes_files_; }
  // Whether the files were written: by the first redo (writes_files()), by write_files(), or by the caller that
  // marked it so (mark_written: the editor's Recorder for anim.record).
  bool files_written() const { return written_; }
  void mark_written() { written_ = true; }
  // The file or folder the command writes (absolute; known after parsing), for messages and the History panel.
  virtual std::filesystem::path output_path() const = 0;
  // Whether write_files() can write the files itself (volume.export); false when its caller writes them
  // (anim.record: the editor records from the scene as it was at that entry).
  virtual bool writes_itself() const { return false; }
  // Writes the files from what the first redo computed (the scene as it was at that entry), the bytes a redo with
  // writing on would have written. Requires a redo first. Throws CommandError (field "path") when a file cannot be
  // written, or when !writes_itself().
  virtual void write_files() { throw CommandError("this command's files are written by its caller", "cmd"); }

 protected:
  bool writes_files_ = true;
  bool written_ = false;
};

// A FileOutput that writes one file itself from what its redo computed (volume.export, ddm.export): the redo hands
// keep_writer() a function that writes that result to a path; it runs then when writes_files(), and write_files()
// runs it again later (the same bytes).
class FileExport : public FileOutput {
 public:
  // `file`: the line's path resolved by CommandContext::resolve_output (absolute, inside the output folder).
  explicit FileExport(std::filesystem::path file) : file_(std::move(file)) {}
  std::filesystem::path output_path() const override { return file_; }
  bool writes_itself() const override { return true; }
  // Throws CommandError: field "object" before a redo, "path" when the file cannot be written.
  void write_files() override {
    if (!writer_) throw CommandError(file_.filename().string() + " was not exported yet: nothing to write", "object");
    try {
      writer_(file_);
    } catch (const CommandError&) {
      throw;
    } catch (const std::exception& e) {
      throw CommandError(std::string("cannot write ") + file_.string() + ": " + e.what(), "path");
    }
    mark_written();
  }

  // Parses `line` as command C, whose params P have a `path`, resolved by CommandContext::resolve_output (throws
  // CommandError "path" when it leaves the output folder).
  template <class C>
  static CommandPtr parse_with_output(const nlohmann::json& line, const CommandContext& ctx) {
    auto p = C::schema().parse(line, ctx);
    std::filesystem::path file = ctx.resolve_output(p.path, "path");
    return std::make_unique<C>(std::move(p), std::move(file));
  }

 protected:
  using Writer = std::function<void(const std::filesystem::path&)>;
  // Keeps `writer` (it creates the file's folder and writes the result) and writes the file now when writes_files().
  void keep_writer(Writer writer) {
    writer_ = std::move(writer);
    if (!writes_files()) return;
    writer_(file_);
    mark_written();
  }

 private:
  std::filesystem::path file_;
  Writer writer_;
};

// `command` as a FileOutput, or null when it writes no files.
inline FileOutput* file_output(Command& command) { return dynamic_cast<FileOutput*>(&command); }
inline const FileOutput* file_output(const Command& command) { return dynamic_cast<const FileOutput*>(&command); }

}  // namespace trispline::core

#include "core/params/command_context.h"

namespace trispline::core {

std::filesystem::path CommandContext::resolve(const std::string& path) const {
  const std::filesystem::path p(path);
  return p.is_absolute() || base_dir.empty() ? p : base_dir / p;
}

std::filesystem::path CommandContext::resolve_output(const std::string& path, const char* field) const {
  namespace fs = std::filesystem;
  const auto refuse = [&](const std::string& why) {
    throw CommandError(std::string("field '") + field + "': " + why, field);
  };
  if (path.empty()) refuse("must not be empty");
  for (const char c : path)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F) refuse("an output path must not hold control characters");
  const fs::path p(path);
  if (p.is_absolute())
    refuse("'" + path +
           "' is absolute: a log writes only under its output folder (replay's --out, the scene's "
           "folder), so an output path is relative to it");
  std::error_code ec;
  const fs::path& dir = output_dir.empty() ? base_dir : output_dir;
  const fs::path root = fs::weakly_canonical(fs::absolute(dir.empty() ? fs::path(".") : dir, ec), ec);
  if (ec) refuse("the output folder '" + dir.string() + "' cannot be resolved: " + ec.message());
  const fs::path target = fs::weakly_canonical(root / p, ec);
  if (ec) refuse("'" + path + "' cannot be resolved: " + ec.message());
  // Component by component: "/out2/x" is not under "/out".
  auto t = target.begin();
  for (auto r = root.begin(); r != root.end() && !r->empty(); ++r, ++t)
    if (t == target.end() || *t != *r)
      refuse("'" + path + "' leaves the output folder '" + root.string() + "' (it resolves to '" + target.string() +
             "'): a log writes only under its output folder");
  if (t == target.end() || target.filename().empty() || fs::is_directory(target, ec))
    refuse("'" + path + "' names a folder, not a file");
  // weakly_canonical follows the links that lead somewhere; a link left in the result dangles, and a write through
  // it would create its target wherever it points.
  fs::path prefix = root;
  for (; t != target.end(); ++t)
    if (prefix /= *t; fs::is_symlink(fs::symlink_status(prefix, ec)))
      refuse("'" + path + "' goes through the dangling symlink '" + prefix.string() +
             "': a log writes only under its "
             "output folder");
  return target;
}

}  // namespace trispline::core

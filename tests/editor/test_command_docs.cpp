// docs/commands.md's parameter tables are generated from the commands' declarations: the committed file must be
// what `trispline commands --docs docs/commands.md` writes, and every declared command must have its table there.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "editor/commands/command_docs.h"
#include "editor/commands/command_registry.h"

namespace fs = std::filesystem;
using namespace trispline;

namespace {

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(CommandDocs, CommittedTablesAreTheGeneratedOnes) {
  const fs::path doc = fs::path(TRISPLINE_SOURCE_DIR) / "docs" / "commands.md";
  const std::string text = read_text(doc);
  ASSERT_FALSE(text.empty()) << doc;
  const std::string generated = editor::with_generated_tables(text, editor::CommandRegistry::builtin());
  EXPECT_EQ(text, generated) << "docs/commands.md is out of date: run `trispline commands --docs docs/commands.md`";
}

TEST(CommandDocs, EveryDeclaredCommandHasItsTable) {
  const std::string text = read_text(fs::path(TRISPLINE_SOURCE_DIR) / "docs" / "commands.md");
  const editor::CommandRegistry& registry = editor::CommandRegistry::builtin();
  for (const std::string& id : registry.ids()) {
    if (!registry.declared(id)) continue;
    EXPECT_NE(text.find("<!-- params: " + id + " -->"), std::string::npos) << id << " has no generated table";
    EXPECT_FALSE(registry.params(id).empty()) << id;
  }
}

TEST(CommandDocs, TableListsEachFieldWithDefaultRangeAndUnit) {
  const std::string table = editor::params_table(editor::CommandRegistry::builtin(), "place.sketch");
  EXPECT_NE(table.find("| `width` | `number` | required | > 0 | world units |"), std::string::npos) << table;
  EXPECT_NE(table.find("| `springs.threshold_deg` | `number` | `2` | (0, 180) | degrees |"), std::string::npos)
      << table;
  EXPECT_NE(table.find("| `length_axis` | `x\\|y\\|z` | `x` |"), std::string::npos) << table;
}

TEST(CommandDocs, UnfinishedBlockIsAnError) {
  EXPECT_THROW(editor::with_generated_tables("<!-- params: camera.set -->\n", editor::CommandRegistry::builtin()),
               std::runtime_error);
  EXPECT_THROW(
      editor::with_generated_tables("<!-- params: no.such -->\n<!-- /params -->", editor::CommandRegistry::builtin()),
      std::runtime_error);
}

}  // namespace

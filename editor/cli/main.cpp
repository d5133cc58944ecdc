#include "editor/cli/cli.h"

int main(int argc, char** argv) { return trispline::editor::run_cli(argc, argv); }

#!/usr/bin/env bash
# The main menu closes after a pick (a check item, and a choice in the View menu's FFD evaluator combo, which ImGui
# would leave open) and on Esc; the View menu's label shows a single '&'.
source "$(dirname "$0")/gui_lib.sh"
gui_start
gui_click_item menu.View
gui_wait '.popups | length > 0' "the View menu opens"
gui_check '.items["menu.Scene & History panels"] != null' "'Scene & History panels' (one ampersand)"
gui_click_item menu.Grid
gui_wait '.popups | length == 0' "the menu closes after picking Grid"

gui_click_item menu.View
gui_wait '.popups | length > 0' "the View menu opens again"
gui_click_item "menu.FFD evaluator"
gui_wait '.items["menu.FFD evaluator.CPU reference"] != null' "the FFD evaluator list opens"
gui_click_item "menu.FFD evaluator.CPU reference"
gui_wait '.popups | length == 0' "the menu closes after choosing an FFD evaluator"

gui_click_item menu.File
gui_wait '.popups | length > 0' "the File menu opens"
gui_key Escape
gui_wait '.popups | length == 0' "Esc closes the menu"
gui_pass

#!/usr/bin/env bash
# Splitting around an obstacle in the real editor (tests/logs/dffd_clearance.jsonl: a sphere with a cylinder standing
# through it): select the sphere, the Split (DFFD) tool, tick the cylinder, type a kernel width, Split → one dffd.split
# in History and the session log as typed; the split left no vertex inside the cylinder and the Log says how the
# lattice was refined to get there; Ctrl+Z takes it back.
source "$(dirname "$0")/gui_lib.sh"
gui_start "$GUI_ROOT/tests/logs/dffd_clearance.jsonl"
gui_wait '(.objects | length) == 2' "the log opens with the sphere and the cylinder"
gui_click_item scene.object.ball
gui_wait '.selected == "ball"' "the sphere is selected"
gui_click_item "tool.Split (DFFD)"
gui_wait '.tool == "Split (DFFD)"' "the Split (DFFD) tool is active"
gui_click_item dffd.obstacle.tool
gui_wait '.values["dffd.obstacles"] == "tool"' "one click ticks the cylinder"
n="$(gui_q '.history.applied')"
gui_scroll_into_view dffd.split
gui_click_item dffd.split
gui_wait ".history.applied == $((n + 1))" "Split adds one history entry" 120
gui_wait_logged '.cmd == "dffd.split" and .object == "ball" and .obstacles == ["tool"] and ((.clearance // 0) == 0)' \
  "dffd.split logged as the panel set it (no clearance typed)"
gui_wait '.log | map(select(test("ball: [0-9]+ vertices were inside an obstacle; the lattice was refined"))) | length == 1' \
  "the Log says the lattice was refined to clear the cylinder"
gui_shot split
gui_key ctrl+z
gui_wait ".history.applied == $n" "Ctrl+Z takes the split back"
gui_pass

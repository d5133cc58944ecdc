#!/usr/bin/env bash
# The Timeline shows every kind of key: with the morphing, walking teapot tiles selected, their ddm.animate keys
# (morph and offset) are teal diamonds beside the object's own offset keys, and hovering one names its channel.
source "$(dirname "$0")/gui_lib.sh"
gui_start "$GUI_ROOT/assets/scenes/seed/teapot_morph.jsonl"
gui_wait '(.history.labels | length) >= 3' "the teapot morph scene is open" 90
gui_click_item scene.object.pot
gui_wait '.selected == "pot"' "pot selected"
gui_wait '.values["timeline.channel_keys"] == "4"' "the Timeline has the layer's four keys (morph 1, 72; offset 1, 96)"
gui_shot channel_keys
gui_pass

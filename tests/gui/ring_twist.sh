#!/usr/bin/env bash
# The Select tool's Ring lattice section (seed Figs. 4.5–4.6): select the default scene's teapot, open Ring lattice,
# type a twist of 180 degrees, Bind to ring → one lattice.ring in History and the session log with that twist (a
# Möbius band: the object's second turn runs upside down beneath the first); a twist of 45 is refused with the reason
# in the Log and nothing added to History.
source "$(dirname "$0")/gui_lib.sh"
gui_start "$GUI_ROOT/assets/scenes/default.jsonl"
gui_wait '(.history.labels | length) >= 4' "the default scene is open"
gui_click_item scene.object.teapot
gui_wait '.selected == "teapot"' "teapot selected"
gui_scroll_into_view select.ring
gui_click_item select.ring
gui_wait '.items["lattice.ring.twist_deg"] != null' "Ring lattice opens with its Twist field"

# type_field NAME VALUE: one click enters text editing, VALUE replaces the value, Enter applies it.
type_field() {
  gui_scroll_into_view "$1"
  gui_click_item "$1"
  gui_wait '.typing' "one click on $1 types"
  gui_type "$2"
  gui_key Return
  gui_wait '.typing | not' "$1 = $2 applied"
}
type_field lattice.ring.twist_deg 180
n="$(gui_q '.history.labels | length')"
gui_scroll_into_view select.ring.bind
gui_click_item select.ring.bind
gui_wait "(.history.labels | length) == $((n + 1))" "Bind to ring adds one history entry" 60
gui_wait_logged '.cmd == "lattice.ring" and .object == "teapot" and .twist_deg == 180' \
  "lattice.ring logged with the typed twist"
gui_shot bound

# A twist that is not a multiple of 90 cannot close the lattice: refused, the Log says why, History unchanged.
type_field lattice.ring.twist_deg 45
gui_scroll_into_view select.ring.bind
gui_click_item select.ring.bind
gui_wait '.log | map(select(test("multiple of 90"))) | length >= 1' "the Log says the twist must be a multiple of 90"
gui_check "(.history.labels | length) == $((n + 1))" "the refused twist adds nothing to History"
gui_pass

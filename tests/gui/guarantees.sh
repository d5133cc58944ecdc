#!/usr/bin/env bash
# View > Error bounds and View > Fold certificate on the placed bunny of the default scene: the heat map and the
# certificate are computed, follow a Press drag live, and a press with Keep fold-free (typed strength far too strong)
# is logged with keep_fold_free, limited, and leaves the lattice certified.
source "$(dirname "$0")/gui_lib.sh"
gui_start "$GUI_ROOT/assets/scenes/default.jsonl"
gui_wait '(.history.labels | length) >= 4' "the default scene is open"
gui_click_item scene.object.bunny
gui_wait '.selected == "bunny"' "bunny selected"

gui_click_item menu.View
gui_wait '.popups | length > 0' "the View menu opens"
gui_click_item "menu.Error bounds"
gui_wait '.guarantees.error_bounds == true and .guarantees.object == "bunny" and .guarantees.triangles > 10000' \
  "the error heat map of the bunny is computed" 60
gui_check '.guarantees.max_bound > 0 and .guarantees.unbounded == 0' "every triangle has a finite bound (order 4/3)"
gui_click_item menu.View
gui_wait '.popups | length > 0' "the View menu opens again"
gui_click_item "menu.Fold certificate"
gui_wait '.guarantees.certificate == "fold_free" and .guarantees.cell_segments > 0' \
  "the placed bunny's lattice is certified fold-free and its cells are drawn" 60

# The Press tool with Keep fold-free and a strength far beyond what the lattice takes.
x0="$(gui_q '.object_centroid_px.bunny[0] | floor')"; y0="$(gui_q '.object_centroid_px.bunny[1] | floor')"
x="$x0"; y="$y0"
gui_move "$x" "$y"
gui_frames 1
gui_key e
gui_wait '.tool == "Press"' "E picks the Press tool"
gui_click_item press.keep_fold_free
gui_wait '.values["press.keep_fold_free"] == "1"' "Keep fold-free is ticked"
gui_click_item press.strength
gui_wait '.typing' "one click on Strength enters text editing"
gui_type "0.4"
gui_key Return
gui_wait '(.typing | not) and (.values["press.strength"] | tonumber) == 0.4' "strength 0.4 typed"

n="$(gui_q '.history.labels | length')"
updates="$(gui_q '.guarantees.updates')"
# press_down_left: the mouse down on the bunny once the tool shows its brush there — over its centroid or, where a
# window covers that (the timing overlay grows and shrinks with the lines of its figures), over the first point near
# it where the brush shows — then three moves down and to the left, away from the timing overlay above (a release over
# it would go to the overlay, not to the tool), two frames each: on a loaded machine X events that arrive within one
# frame are one move. The button stays down.
press_down_left() {
  local i d dx dy
  for d in "0 0" "0 25" "-25 25" "0 45" "-30 0" "0 -25"; do
    read -r dx dy <<<"$d"
    x=$((x0 + dx)) y=$((y0 + dy))
    gui_move "$x" "$y"
    gui_frames 2
    [ "$(gui_q '.overlays.spheres > 0')" = true ] && break
  done
  gui_wait '.overlays.spheres > 0' "the brush sphere shows over the bunny before the button goes down" 30
  xdotool mousedown 1
  gui_frames 3
  for i in 1 2 3; do
    gui_move $((x - 4 * i)) $((y + 2 * i))
    gui_frames 2
  done
}
press_down_left
gui_wait ".guarantees.live == true and .guarantees.updates > $updates and .guarantees.certificate == \"fold_free\"" \
  "during the drag the view shows the pressed (limited, still certified) lattice" 60
xdotool mouseup 1
gui_wait "(.history.labels | length) == $((n + 1))" "one history entry for the drag" 90
gui_wait_logged '.cmd == "lattice.press" and .keep_fold_free == true and .strength == 0.4' \
  "lattice.press logged with keep_fold_free and the typed strength"
gui_wait '.guarantees.live == false and .guarantees.certificate == "fold_free"' \
  "after the press the bunny's own lattice is shown, certified fold-free" 60

# A sharp falloff, strength 0.6 and radius 0.3, the same drag again and again: each press is limited further, until the
# lattice cannot move that way any more and the press is refused (the panel says why during the drag, the Log at
# release), never applied as an invisible one.
gui_click_item press.falloff
gui_click_item press.falloff.sharp
gui_wait '.values["press.falloff"] == "sharp"' "the sharp falloff is picked"
gui_click_item press.strength
gui_wait '.typing' "one click on Strength enters text editing"
gui_type "0.6"
gui_key Return
gui_wait '(.typing | not) and (.values["press.strength"] | tonumber) == 0.6' "strength 0.6 typed"
gui_click_item press.radius
gui_wait '.typing' "one click on Radius enters text editing"
gui_type "0.3"
gui_key Return
gui_wait '(.typing | not) and (.values["press.radius"] | tonumber) == 0.3' "radius 0.3 typed"
refused=""
for k in 1 2 3 4 5 6; do
  n="$(gui_q '.history.applied')"
  press_down_left
  gui_frames 3
  during="$(gui_q '.values["press.refusal"] // ""')"
  xdotool mouseup 1
  gui_frames 6
  if [ "$(gui_q '.log | map(select(test("cannot move this way"))) | length')" -ge 1 ]; then
    refused=$k
    [ -n "$during" ] || gui_fail "the panel did not say during the drag why the press would be refused"
    [ "$(gui_q '.history.applied')" = "$n" ] || gui_fail "a refused press added a history entry"
    break
  fi
  gui_wait ".history.applied == $((n + 1))" "drag $k: one more limited press" 90
done
[ -n "$refused" ] || gui_fail "six repeated Keep fold-free presses were never refused"
gui_log "ok: the press was refused at drag $refused, and the panel said why during the drag"
gui_shot refused
gui_pass

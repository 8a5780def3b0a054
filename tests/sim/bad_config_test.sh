#!/usr/bin/env bash
# relplane-sim on bad input: exit 2, exactly one line on stderr naming the file and the key,
# nothing on the bus (the bus is never opened: an unreachable URL would fail otherwise).
# usage: bad_config_test.sh SIM_BINARY DATA_DIR
set -u
sim="$1"
data="$2"
fail=0
check() {  # FILE EXPECTED_TEXT...
  local file="$1"
  shift
  local err rc
  err="$("$sim" --config "$file" --lcm-url "udpm://239.255.76.67:1?ttl=0" 2>&1 >/dev/null)"
  rc=$?
  if [ "$rc" != 2 ]; then echo "FAIL $file: exit $rc, expected 2"; fail=1; fi
  if [ "$(printf '%s\n' "$err" | wc -l)" != 1 ]; then echo "FAIL $file: not one line: $err"; fail=1; fi
  for text in "$@"; do
    case "$err" in
      *"$text"*) ;;
      *) echo "FAIL $file: '$text' missing in: $err"; fail=1 ;;
    esac
  done
  echo "ok $file: $err"
}
check "$data/unknown_key.yaml" "unknown_key.yaml:5" "sim.sensor.widht"
check "$data/negative_rate.yaml" "negative_rate.yaml:3" "sim.rate_hz"
check "$data/empty_world.yaml" "empty_world.yaml:4" "sim.world.generators"
check "$data/no_such_file.yaml" "no_such_file.yaml" "--config"
# --check-config on a good scenario exits 0 without touching the bus.
"$sim" --config "$data/../../../scenarios/hallway_loop.yaml" --check-config || {
  echo "FAIL --check-config on hallway_loop.yaml"
  fail=1
}
exit $fail

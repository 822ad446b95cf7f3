# Shell functions the integration test scripts share; sourced after they set $work and $case_name
# and define fail().

# Fails the case when a role process of one of its runs (under $work/$case_name) is still there.
no_leftovers() {
  sleep 0.5
  if pgrep -f "wsntrack-.*--run-dir $work/$case_name" >/dev/null; then
    pgrep -af "wsntrack-.*--run-dir $work/$case_name" >&2
    fail "processes left behind"
  fi
}

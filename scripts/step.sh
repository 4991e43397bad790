# Sourced by the scripts: `step WHAT COMMAND...` prints "== WHAT", runs COMMAND, and while it runs
# prints a line every 8 s, so that no step is silent for long on a terminal or in a CI log.
step() {
  local what="$1" started=$SECONDS pid
  shift
  echo "== $what" >&2
  "$@" &
  pid=$!
  while ! wait_briefly "$pid" 8; do echo "   ... $what ($((SECONDS - started)) s)" >&2; done
  wait "$pid"
}

# True once process $1 has ended, false if it still runs after $2 seconds.
wait_briefly() {
  local i
  for ((i = 0; i < $2 * 4; i++)); do
    kill -0 "$1" 2>/dev/null || return 0
    sleep 0.25
  done
  ! kill -0 "$1" 2>/dev/null
}

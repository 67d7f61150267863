#!/usr/bin/env bash
# Ctrl-C on `deepnav serve` while clients' sessions are open (one TCP, one UDP): serve must
# exit 0 (it exited 1 with "Invalid argument": the shutdown joined a session's thread
# twice), and each client must get the end-of-stream frame, not a connection that just
# drops (a receiver would keep reconnecting to it).
#   usage: serve_interrupt.sh <deepnav binary> <source dir>
source "$(dirname "$0")/lib/harness.sh" "$@"
head -c 4000000 /dev/urandom > "$work/if.bin"  # 20 s of ibyte at 100 kHz, paced in real time
start_background server "$deepnav" serve --file "$work/if.bin" --format ibyte --fs 100000 --tcp 0 --udp 0 --pace 1 \
  --port-file "$work/ports" 2> "$work/serve.log"
tcp_port=$(port_from "$work/ports" tcp)
udp_port=$(port_from "$work/ports" udp)
start_background tcp_client "$python" -S "$peers/stream_client.py" tcp "$tcp_port" "$work/tcp_ready" > "$work/tcp.out" 2>&1
start_background udp_client "$python" -S "$peers/stream_client.py" udp "$udp_port" "$work/udp_ready" > "$work/udp.out" 2>&1
for _ in $(seq 150); do [[ -e $work/tcp_ready && -e $work/udp_ready ]] && break; sleep 0.1; done
[[ -e $work/tcp_ready && -e $work/udp_ready ]] || abort "the clients got no frames: $(cat "$work/serve.log")"

kill -INT $server
for _ in $(seq 100); do kill -0 $server 2>/dev/null || break; sleep 0.1; done
if kill -0 $server 2>/dev/null; then abort "serve still running 10 s after SIGINT"; fi
status=0
reap $server || status=$?
check "serve exits 0 on SIGINT (status $status)" '[[ $status -eq 0 ]]'
status=0
reap $tcp_client || status=$?
check "the TCP client got the end-of-stream frame: $(cat "$work/tcp.out")" '[[ $status -eq 0 ]]'
status=0
reap $udp_client || status=$?
check "the UDP client got the end-of-stream frame: $(cat "$work/udp.out")" '[[ $status -eq 0 ]]'
check "serve logs the sessions' end" 'grep -q "session ended (server stopping)" "$work/serve.log"'
[[ $harness_failures -eq 0 ]] || cat "$work/serve.log"
finish

#!/usr/bin/env bash
# Ctrl-C on `deepnav serve` while clients' sessions are open (one TCP, one UDP): serve must
# exit 0 (it exited 1 with "Invalid argument": the shutdown joined a session's thread
# twice), and each client must get the end-of-stream frame, not a connection that just
# drops (a receiver would keep reconnecting to it).
#   usage: serve_interrupt.sh <deepnav binary> <source dir>
set -uo pipefail
deepnav=$1
work=$(mktemp -d)
server=
trap '[[ -n $server ]] && kill $server 2>/dev/null; rm -rf "$work"' EXIT
fail() { echo "FAIL $*"; exit 1; }

cat > "$work/client.py" <<'PY'
# tcp|udp PORT READY_FILE: subscribes, reads the header and two frames, creates READY_FILE,
# then reads until the end-of-stream frame (prints "end of stream") or until the
# connection drops or 10 s of silence (prints what happened).
import socket, struct, sys, time
kind, port, ready = sys.argv[1], int(sys.argv[2]), sys.argv[3]
request = b"DNRQ" + struct.pack("<HHq", 1, 0, 0)
frames = 0
def frame_seen(hdr):
    global frames
    assert hdr[:4] == b"DNFR", hdr[:4]
    length, seq, first, flags = struct.unpack("<IQqI", hdr[4:28])
    if flags & 1:
        print(f"{kind}: end of stream after {frames} frames")
        sys.exit(0)
    frames += 1
    if frames == 2:
        open(ready, "w").close()
    return length
if kind == "tcp":
    s = socket.create_connection(("127.0.0.1", port), timeout=10)
    s.sendall(request)
    def exact(n):
        data = b""
        while len(data) < n:
            part = s.recv(n - len(data))
            if not part:
                print(f"{kind}: connection closed without an end-of-stream frame after {frames} frames")
                sys.exit(1)
            data += part
        return data
    assert exact(56)[:4] == b"DNIF"
    while True:
        exact(frame_seen(exact(28)))
else:
    s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    s.settimeout(0.5)
    last_request, silent_since = 0.0, time.time()
    while time.time() - silent_since < 10:
        if time.time() - last_request > 1:  # subscribe, then keep alive
            s.sendto(request, ("127.0.0.1", port))
            last_request = time.time()
        try:
            d = s.recv(65536)
        except socket.timeout:
            continue
        silent_since = time.time()
        if d[:4] == b"DNFR":
            frame_seen(d[:28])
    print(f"{kind}: no end-of-stream frame after {frames} frames (10 s of silence)")
    sys.exit(1)
PY

head -c 4000000 /dev/urandom > "$work/if.bin"  # 20 s of ibyte at 100 kHz, paced in real time
"$deepnav" serve --file "$work/if.bin" --format ibyte --fs 100000 --tcp 0 --udp 0 --pace 1 \
  --port-file "$work/ports" 2> "$work/serve.log" &
server=$!
for _ in $(seq 100); do [[ -s $work/ports ]] && break; sleep 0.1; done
tcp_port=$(awk '$1 == "tcp" {print $2}' "$work/ports" 2>/dev/null)
udp_port=$(awk '$1 == "udp" {print $2}' "$work/ports" 2>/dev/null)
[[ -n $tcp_port && -n $udp_port ]] || fail "serve did not report its ports"
python3 "$work/client.py" tcp "$tcp_port" "$work/tcp_ready" > "$work/tcp.out" 2>&1 &
tcp_client=$!
python3 "$work/client.py" udp "$udp_port" "$work/udp_ready" > "$work/udp.out" 2>&1 &
udp_client=$!
for _ in $(seq 150); do [[ -e $work/tcp_ready && -e $work/udp_ready ]] && break; sleep 0.1; done
[[ -e $work/tcp_ready && -e $work/udp_ready ]] || fail "the clients got no frames: $(cat "$work/serve.log")"

kill -INT $server
status=0
for _ in $(seq 100); do kill -0 $server 2>/dev/null || break; sleep 0.1; done
kill -0 $server 2>/dev/null && fail "serve still running 10 s after SIGINT"
wait $server || status=$?
server=
[[ $status -eq 0 ]] || fail "serve exit status $status after SIGINT: $(cat "$work/serve.log")"
wait $tcp_client || fail "$(cat "$work/tcp.out")"
wait $udp_client || fail "$(cat "$work/udp.out")"
grep -q "session ended (server stopping)" "$work/serve.log" || fail "serve did not log the sessions' end: $(cat "$work/serve.log")"
echo "ok   serve exited 0 on SIGINT; $(cat "$work/tcp.out"); $(cat "$work/udp.out")"

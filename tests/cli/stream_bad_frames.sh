#!/usr/bin/env bash
# Frames whose sequence number or sample index lie beyond what the stream's header allows:
# a UDP frame numbered 2^63 (its loss accounting once looped 9e18 times, and the process
# never exited), frames whose index jumps by 1e15 samples over UDP (a hang) and TCP
# (std::bad_alloc, no products). Each run must end within seconds with exit status 1, a
# message naming the stream and the field, and the products written up to there.
#   usage: stream_bad_frames.sh <deepnav binary> <source dir>
set -uo pipefail
deepnav=$1
work=$(mktemp -d)
helper=
trap '[[ -n $helper ]] && kill $helper 2>/dev/null; rm -rf "$work"' EXIT
fail=0

cat > "$work/stream.py" <<'PY'
# udp MODE PORT: sends a framed stream (2 s of noise at 4.092 Msps, 8192-byte frames) to a
# listening receiver; tcp MODE PORTFILE: serves it to one client. MODE: seqjump (one extra
# frame numbered 2^63 after frame 200), idxjump (frames from 200 on have index + 1e15).
import os, random, socket, struct, sys, time
kind, mode, where = sys.argv[1:4]
rng = random.Random(1)
def header(maxp):
    return b'DNIF' + struct.pack('<HHBBHIddqiId', 1, 56, 0, 0, 0, maxp, 4092000.0, 0.0, 0, 0, 0, 0.0)
def frame(seq, first, payload, flags=0):
    return b'DNFR' + struct.pack('<IQqI', len(payload), seq, first, flags) + payload
payload = bytes(rng.getrandbits(8) for _ in range(8192))
frames, idx = [], 0
for seq in range(1000):
    frames.append(frame(seq, idx + (10**15 if mode == 'idxjump' and seq >= 200 else 0), payload))
    if mode == 'seqjump' and seq == 200:
        frames.append(frame(2**63, 10**6, payload))
    idx += 4096
frames.append(frame(1000, idx, b'', 1))
if kind == 'udp':
    u = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    dst = ('127.0.0.1', int(where))
    for _ in range(10):  # until the receiver listens
        u.sendto(header(8192), dst)
        time.sleep(0.1)
    for f in frames:
        try:
            u.sendto(f, dst)
        except ConnectionRefusedError:
            break
        time.sleep(0.0002)
else:
    s = socket.socket()
    s.bind(('127.0.0.1', 0))
    s.listen(1)
    open(where + '.tmp', 'w').write(str(s.getsockname()[1]))
    os.rename(where + '.tmp', where)
    c, _ = s.accept()
    c.recv(16)
    try:
        c.sendall(header(8192))
        for f in frames:
            c.sendall(f)
    except (BrokenPipeError, ConnectionResetError):
        pass
PY

free_port() { python3 -c "import socket; s=socket.socket(socket.AF_INET, socket.SOCK_DGRAM); s.bind(('127.0.0.1', 0)); print(s.getsockname()[1])"; }

check() {  # name, rc, message, out dir, fragment
  local name=$1 rc=$2 out=$3 dir=$4 fragment=$5
  if [[ $rc -eq 124 || $rc -eq 137 ]]; then echo "FAIL $name: still running after the time limit"; fail=1; return; fi
  if [[ $rc -ne 1 ]]; then echo "FAIL $name: exit status $rc, expected 1: $out"; fail=1; return; fi
  if [[ $out != *"$fragment"* ]]; then echo "FAIL $name: message lacks '$fragment': $out"; fail=1; return; fi
  if [[ ! -f $dir/summary.json || ! -f $dir/pvt.csv ]]; then echo "FAIL $name: products missing: $(ls "$dir" 2>&1)"; fail=1; return; fi
  if ! python3 -c "import json, sys; s = json.load(open(sys.argv[1])); sys.exit(0 if sys.argv[2] in (s['error'] or '') else 1)" \
       "$dir/summary.json" "$fragment"; then
    echo "FAIL $name: summary.json's error lacks the reason"; fail=1; return
  fi
  echo "ok   $name: $(tail -n 1 <<< "$out")"
}

for mode in seqjump idxjump; do
  port=$(free_port)
  python3 "$work/stream.py" udp $mode "$port" &
  helper=$!
  out=$(timeout -k 3 20 "$deepnav" -q run --input "udp://@127.0.0.1:$port" --week 2190 --out "$work/udp_$mode" 2>&1 >/dev/null)
  rc=$?
  kill $helper 2>/dev/null; wait $helper 2>/dev/null; helper=
  if [[ $mode == seqjump ]]; then
    fragment="sequence number 9223372036854775808 is beyond what its first sample index 1000000 allows"
  else
    fragment="first sample index 1000000000819200 is beyond what its sequence number allows"
  fi
  check "udp_$mode" $rc "$out" "$work/udp_$mode" "$fragment"
done

python3 "$work/stream.py" tcp idxjump "$work/port" &
helper=$!
for _ in $(seq 100); do [[ -s $work/port ]] && break; sleep 0.1; done
out=$(timeout -k 3 20 "$deepnav" -q run --input "tcp://127.0.0.1:$(cat "$work/port")" --week 2190 --reconnect-timeout 1 \
      --out "$work/tcp_idxjump" 2>&1 >/dev/null)
rc=$?
kill $helper 2>/dev/null; wait $helper 2>/dev/null; helper=
check tcp_idxjump $rc "$out" "$work/tcp_idxjump" "first sample index 1000000000819200 is beyond what its sequence number allows"
exit $fail

#!/usr/bin/env python3
"""A loopback server that is not rtl_tcp: it answers one connection with an HTTP status line.

usage: not_rtltcp_server.py PORT_FILE   (writes its port there once it listens)
"""
import socket
import sys

server = socket.socket()
server.bind(("127.0.0.1", 0))
server.listen(1)
with open(sys.argv[1], "w") as f:
    f.write(str(server.getsockname()[1]))
conn, _ = server.accept()
conn.sendall(b"HTTP/1.0 200 OK\r\n\r\n")
conn.recv(100)
conn.close()

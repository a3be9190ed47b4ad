"""Client/server test driver (run by any python3, under an X server):
starts `mpiexec -np N pvserver --force-offscreen-rendering` on a free port,
runs client_server_client.py in pvpython against it, and stops the server.

Usage: test_client_server.py MPIEXEC PVSERVER PVPYTHON NP [THRESHOLD]
"""
import os
import re
import signal
import socket
import subprocess
import sys
import threading
import time

mpiexec, pvserver, pvpython, ranks = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
threshold = sys.argv[5] if len(sys.argv) > 5 else "10"
here = os.path.dirname(os.path.abspath(__file__))

with socket.socket() as s:
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]

server = subprocess.Popen(
    [mpiexec, "--oversubscribe", "-np", str(ranks), pvserver, "--force-offscreen-rendering",
     "--server-port=%d" % port],
    stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, start_new_session=True)
ready = threading.Event()
lines = []


def pump():
    for line in server.stdout:
        lines.append(line)
        if re.search(r"Accepting connection", line):
            ready.set()


threading.Thread(target=pump, daemon=True).start()
status = 1
try:
    if not ready.wait(120):
        print("FAILED: pvserver did not start listening within 120 s:\n" + "".join(lines))
    else:
        print("pvserver (%d ranks) listening on port %d" % (ranks, port))
        client = subprocess.run(
            [pvpython, "--force-offscreen-rendering", os.path.join(here, "client_server_client.py"),
             "127.0.0.1", str(port), str(ranks), threshold], timeout=300)
        status = client.returncode
        try:
            server.wait(60)  # pvserver exits when its client disconnects
        except subprocess.TimeoutExpired:
            print("FAILED: pvserver still running 60 s after the client disconnected")
            status = status or 1
finally:
    if server.poll() is None:
        os.killpg(server.pid, signal.SIGTERM)
        time.sleep(2)
        if server.poll() is None:
            os.killpg(server.pid, signal.SIGKILL)
    print("---- pvserver output ----\n" + "".join(lines[-40:]))
sys.exit(status)

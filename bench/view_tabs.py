"""N clients of a `radflux view` page that do what its script does, without rendering:
each holds the page's event stream (Server-Sent Events) and, whenever a message says a newer
snapshot exists, fetches the newest snapshot (one fetch at a time, as view.js does). Each
client k writes "[1] queued" to PREFIX_k.err once its first message shows the job queued
(bench/watcher_cost.sh waits for that), and ends with the job's final message.
Usage: view_tabs.py URL N PREFIX"""
import json
import sys
import threading
import urllib.request

URL, N, PREFIX = sys.argv[1], int(sys.argv[2]), sys.argv[3]


def tab(k):
    have, said = 0, False
    with urllib.request.urlopen(URL + "events") as events:
        for raw in events:
            line = raw.decode().strip()
            if not line.startswith("data: "):
                continue
            m = json.loads(line[6:])
            if not said and m.get("state") == "JOB_STATE_QUEUED":
                with open(f"{PREFIX}{k}.err", "w") as f:
                    f.write("[1] queued\n")
                said = True
            if m["snapshot_serial"] > have:
                with urllib.request.urlopen(URL + "snapshot") as r:
                    r.read()
                    have = int(r.headers["X-Serial"])
            if m["ended"]:
                return


threads = [threading.Thread(target=tab, args=(k,)) for k in range(N)]
for t in threads:
    t.start()
for t in threads:
    t.join()

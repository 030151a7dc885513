"""Reads a results.mcap with the independent Python `mcap` + `mcap-ros2-support` readers and
checks what uwbsar promises about it (slam/outputs/results_timeline.h):

  check_results_mcap.py run DIR       `map` / `demo`: one /map per solve (summary.json), the
                                      last /map is map.pgm, /path ends at trajectory.tum's end,
                                      loops as in summary.json, ground truth, the SAR mosaic
  check_results_mcap.py session DIR   `map --resume` / `merge`: /map is map.pgm, one path per run
  check_results_mcap.py localize DIR  `localize`: /path is trajectory.tum (from the first fix)

Every mode: the topics' schemas, /tf with map -> odom and odom -> base_link, its log times
strictly increasing and equal to the header stamps. Exits 1 with one line per failure.
"""
import json
import math
import sys
from collections import defaultdict

from mcap.reader import make_reader
from mcap_ros2.decoder import DecoderFactory

SCHEMAS = {
    "/map": "nav_msgs/msg/OccupancyGrid",
    "/uwbsar/sar": "nav_msgs/msg/OccupancyGrid",
    "/uwbsar/sar_image": "sensor_msgs/msg/Image",
    "/path": "nav_msgs/msg/Path",
    "/ground_truth/path": "nav_msgs/msg/Path",
    "/uwbsar/loops": "visualization_msgs/msg/MarkerArray",
    "/tf": "tf2_msgs/msg/TFMessage",
}

failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
    return ok


def read(path):
    """Every message in log-time order: (topic, schema name, log_time, decoded)."""
    with open(path, "rb") as f:
        reader = make_reader(f, decoder_factories=[DecoderFactory()])
        return [(ch.topic, schema.name, msg.log_time, dec)
                for schema, ch, msg, dec in reader.iter_decoded_messages(log_time_order=True)]


def stamp_ns(header):
    return header.stamp.sec * 1000000000 + header.stamp.nanosec


def read_pgm(path):
    """map_server trinary PGM (P5) as nav_msgs values, bottom row first."""
    data = open(path, "rb").read()
    fields, pos = [], 0
    while len(fields) < 4:
        while data[pos:pos + 1].isspace():
            pos += 1
        if data[pos:pos + 1] == b"#":
            pos = data.index(b"\n", pos)
            continue
        end = pos
        while not data[end:end + 1].isspace():
            end += 1
        fields.append(data[pos:end])
        pos = end
    width, height = int(fields[1]), int(fields[2])
    pixels = data[pos + 1:pos + 1 + width * height]
    value = {0: 100, 254: 0, 205: -1}
    rows = [pixels[r * width:(r + 1) * width] for r in range(height)]
    return width, height, [value[p] for row in reversed(rows) for p in row]


def tum_poses(path):
    out = []
    for line in open(path):
        if line.strip() and not line.startswith("#"):
            v = [float(x) for x in line.split()]
            out.append((v[0], v[1], v[2]))
    return out


def check_common(messages, expected_topics):
    by_topic = defaultdict(list)
    for topic, schema, log_time, msg in messages:
        by_topic[topic].append((log_time, msg))
        if topic in SCHEMAS:
            check(schema == SCHEMAS[topic], f"{topic}: schema {schema}, want {SCHEMAS[topic]}")
        elif topic.startswith("/uwbsar/run_"):
            check(schema == "nav_msgs/msg/Path", f"{topic}: schema {schema}")
    for topic in expected_topics:
        check(topic in by_topic, f"{topic}: no message")
    tf = by_topic.get("/tf", [])
    check(len(tf) > 10, f"/tf: only {len(tf)} messages")
    for (t0, _), (t1, _) in zip(tf, tf[1:]):
        if not check(t1 > t0, f"/tf: log time goes from {t0} to {t1}"):
            break
    for log_time, msg in tf:
        pairs = {(t.header.frame_id, t.child_frame_id) for t in msg.transforms}
        check(pairs == {("map", "odom"), ("odom", "base_link")}, f"/tf: frames {pairs}")
        check(all(stamp_ns(t.header) == log_time for t in msg.transforms),
              f"/tf: header stamp differs from log time {log_time}")
        if failures:
            break
    for log_time, msg in by_topic.get("/map", []):
        check(msg.header.frame_id == "map", "/map: frame " + msg.header.frame_id)
        check(len(msg.data) == msg.info.width * msg.info.height, "/map: data size")
    for log_time, msg in by_topic.get("/uwbsar/sar_image", []):
        check(msg.encoding == "mono8" and len(msg.data) == msg.step * msg.height,
              "/uwbsar/sar_image: mono8 size")
    return by_topic


def check_map_is_pgm(grid, folder):
    width, height, values = read_pgm(folder + "/map.pgm")
    check((grid.info.width, grid.info.height) == (width, height),
          f"/map: {grid.info.width} x {grid.info.height}, map.pgm {width} x {height}")
    if (grid.info.width, grid.info.height) == (width, height):
        differ = sum(1 for a, b in zip(grid.data, values) if a != b)
        check(differ == 0, f"/map: {differ} cells differ from map.pgm")


def check_path_ends_like(path_msg, tum, what):
    if not check(len(path_msg.poses) > 1, f"{what}: {len(path_msg.poses)} poses"):
        return
    last = path_msg.poses[-1]
    t, x, y = tum[-1]
    check(abs(stamp_ns(last.header) * 1e-9 - t) < 1e-4, f"{what}: ends at {last.header.stamp}, tum {t}")
    check(math.hypot(last.pose.position.x - x, last.pose.position.y - y) < 1e-3,
          f"{what}: last pose ({last.pose.position.x}, {last.pose.position.y}), tum ({x}, {y})")


def main():
    mode, folder = sys.argv[1], sys.argv[2]
    messages = read(folder + "/results.mcap")
    summary = json.load(open(folder + "/summary.json"))
    if mode == "run":
        by_topic = check_common(messages, SCHEMAS.keys())
        maps = by_topic.get("/map", [])
        solves = summary["optimization"]["solves"]
        check(len(maps) == solves, f"/map: {len(maps)} messages, {solves} solves")
        check(len(by_topic.get("/path", [])) == solves, "/path: one per solve")
        if maps:
            check_map_is_pgm(maps[-1][1], folder)
            check_path_ends_like(by_topic["/path"][-1][1], tum_poses(folder + "/trajectory.tum"),
                                 "/path")
        loops = by_topic.get("/uwbsar/loops", [])
        if loops:
            lines = [m for m in loops[-1][1].markers if m.ns == "loops"]
            points = len(lines[0].points) if lines else 0
            check(points == 2 * summary["loops"]["accepted"],
                  f"/uwbsar/loops: {points} points, {summary['loops']['accepted']} loops")
            anchors = [m for m in loops[-1][1].markers if m.ns == "keyframes"]
            check(anchors and len(anchors[0].points) == summary["keyframes"],
                  "/uwbsar/loops: one sphere per keyframe")
        check(len(by_topic.get("/ground_truth/path", [[0, None]])[0][1].poses) > 10,
              "/ground_truth/path: too short")
        times = [t for _, _, t, _ in messages]
        check(times == sorted(times), "log times not in order")
    elif mode == "session":
        runs = [f"/uwbsar/run_{r['id']}/path" for r in summary["runs"]]
        expected = ["/map", "/uwbsar/sar", "/uwbsar/sar_image", "/path", "/uwbsar/loops", "/tf"]
        by_topic = check_common(messages, expected + runs)
        check(len(by_topic.get("/map", [])) == 1, "/map: one message")
        if by_topic.get("/map"):
            check_map_is_pgm(by_topic["/map"][0][1], folder)
        newest = summary["runs"][-1]
        if by_topic.get("/path"):
            check_path_ends_like(by_topic["/path"][0][1], tum_poses(folder + "/" + newest["tum"]),
                                 "/path")
    elif mode == "localize":
        by_topic = check_common(messages, ["/map", "/uwbsar/sar", "/path", "/tf"])
        tum = tum_poses(folder + "/trajectory.tum")
        if by_topic.get("/path"):
            path = by_topic["/path"][-1][1]
            check_path_ends_like(path, tum, "/path")
            first = path.poses[0]
            check(abs(stamp_ns(first.header) * 1e-9 - tum[0][0]) < 1e-4,
                  f"/path: starts at {first.header.stamp}, trajectory.tum at {tum[0][0]}")
    else:
        failures.append("unknown mode " + mode)
    for f in failures:
        print("FAIL", f)
    if not failures:
        print(f"ok: {len(messages)} messages")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()

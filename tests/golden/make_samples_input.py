#!/usr/bin/env python3
"""Read the bundled samples (assets/reach10.mcap, assets/planted8.mcap: ROS 2
geometry_msgs/PoseStamped in CDR) with the mcap package and write input_samples.json in
input.json's shape: per set, each topic's header stamps (integer ns) and positions."""
import json
import os
import struct

from mcap.reader import make_reader

HERE = os.path.dirname(os.path.abspath(__file__))
ASSETS = os.path.join(HERE, "..", "..", "assets")


def pose_stamped(data):
    """(stamp_ns, [x, y, z]) of a CDR PoseStamped (little-endian encapsulation)."""
    if data[1] != 1:
        raise ValueError("expected little-endian CDR")
    body = data[4:]
    sec, nsec, n = struct.unpack_from("<iII", body, 0)
    off = 12 + n
    off += (-off) % 8
    x, y, z = struct.unpack_from("<3d", body, off)
    return sec * 1_000_000_000 + nsec, [x, y, z]


def read(path):
    demos = {}
    with open(path, "rb") as fh:
        for _, channel, message in make_reader(fh).iter_messages(log_time_order=False):
            stamp, pos = pose_stamped(message.data)
            d = demos.setdefault(channel.topic, dict(name=channel.topic, stamps_ns=[], positions=[]))
            d["stamps_ns"].append(stamp)
            d["positions"].append(pos)
    return [demos[t] for t in sorted(demos)]


def main():
    sets = {name: read(os.path.join(ASSETS, name + ".mcap")) for name in ("reach10", "planted8")}
    path = os.path.join(HERE, "input_samples.json")
    with open(path, "w") as fh:
        json.dump(dict(sets=sets), fh)
    print("wrote", path, os.path.getsize(path), "bytes")


if __name__ == "__main__":
    main()

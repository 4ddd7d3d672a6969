#!/usr/bin/env python3
"""Writes the ROS 1 bag fixtures of core/tests/rosbag1.rs and app/tests/cli_bags.rs
with the `rosbags` PyPI package (an independent writer), and their ROS 2 MCAP
conversions with its `rosbags-convert`.

    python3 -m venv /tmp/venv && /tmp/venv/bin/pip install rosbags==0.11.9 numpy
    /tmp/venv/bin/python core/tests/bags/make_bags.py

Three reach demonstrations tracked at 90 Hz (a VIVE controller as
PoseStamped, turning as it goes), each with /tf (base -> tracker) and
/tf_static (world -> base), and a custom message type beside the poses:
  reach/reach_{1,2,3}.bag     one per compression: none, bz2, lz4
  converted/reach_{1,2,3}/    rosbags-convert of each to ROS 2 MCAP
  odd/unindexed.bag           reach_1 with no index and its last chunk cut
                              short (a recording that was killed)
  odd/corrupt.bag             reach_3 (lz4) with bytes of its first chunk
                              flipped
  odd/killed_lz4.bag          reach_3 (lz4) as a killed recording leaves it:
                              no index, its last chunk's header still
                              saying size 0, the file ending inside it
  types.bag                   reach 1 as PoseWithCovarianceStamped,
                              PointStamped, TransformStamped and Odometry
"""

import math
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
from rosbags.rosbag1 import Writer
from rosbags.typesys import Stores, get_types_from_msg, get_typestore

HERE = Path(__file__).resolve().parent
BUTTON = "bool pressed\nstring label\n"


def typestore():
    store = get_typestore(Stores.ROS1_NOETIC)
    store.register(get_types_from_msg(BUTTON, "my_msgs/msg/Button"))
    if "tf2_msgs/msg/TFMessage" not in store.types:
        store.register(
            get_types_from_msg("geometry_msgs/TransformStamped[] transforms", "tf2_msgs/msg/TFMessage")
        )
    return store


def demo(k):
    """Stamps (ns) and poses of reach k: a minimum-jerk reach with an arc."""
    rng = np.random.default_rng(7 + k)
    n = 100 + 8 * k
    t0 = 1_700_000_000_000_000_000 + k * 30_000_000_000
    stamps = [t0 + round(i * 1e9 / 90.0) for i in range(n)]
    start = np.array([0.35, -0.2, 0.95]) + 0.01 * rng.standard_normal(3)
    goal = start + np.array([0.25, 0.28, 0.14]) * (1.0 + 0.1 * k)
    poses = []
    for i in range(n):
        u = i / (n - 1)
        s = u**3 * (10 - 15 * u + 6 * u * u)
        p = start + s * (goal - start) + np.array([0.0, -0.02, 0.04]) * math.sin(math.pi * s)
        p = p + 2e-4 * rng.standard_normal(3)
        angle = 0.2 + 1.2 * s
        axis = np.array([0.0, 0.6, 0.8])
        q = np.concatenate([axis * math.sin(angle / 2), [math.cos(angle / 2)]])
        poses.append((p, q))
    return stamps, poses


def header(store, stamp, frame):
    Header = store.types["std_msgs/msg/Header"]
    Time = store.types["builtin_interfaces/msg/Time"]
    return Header(seq=0, stamp=Time(sec=stamp // 10**9, nanosec=stamp % 10**9), frame_id=frame)


def write(path, k, compression):
    store = typestore()
    T = store.types
    stamps, poses = demo(k)
    path.unlink(missing_ok=True)
    writer = Writer(path)
    if compression != "none":
        writer.set_compression(getattr(Writer.CompressionFormat, compression.upper()))
    writer.chunk_threshold = 8 * 1024
    with writer:
        pose_c = writer.add_connection("/vive/controller", "geometry_msgs/msg/PoseStamped", typestore=store)
        tf_c = writer.add_connection("/tf", "tf2_msgs/msg/TFMessage", typestore=store)
        static_c = writer.add_connection("/tf_static", "tf2_msgs/msg/TFMessage", typestore=store, latching=1)
        button_c = writer.add_connection("/vive/button", "my_msgs/msg/Button", typestore=store)

        def transform(stamp, parent, child, p, q):
            return T["geometry_msgs/msg/TransformStamped"](
                header=header(store, stamp, parent),
                child_frame_id=child,
                transform=T["geometry_msgs/msg/Transform"](
                    translation=T["geometry_msgs/msg/Vector3"](x=p[0], y=p[1], z=p[2]),
                    rotation=T["geometry_msgs/msg/Quaternion"](x=q[0], y=q[1], z=q[2], w=q[3]),
                ),
            )

        quarter = [0.0, 0.0, math.sin(math.pi / 4), math.cos(math.pi / 4)]
        static = T["tf2_msgs/msg/TFMessage"](transforms=[transform(stamps[0], "world", "base", [1.0, 0.0, 0.0], quarter)])
        writer.write(static_c, stamps[0], store.serialize_ros1(static, "tf2_msgs/msg/TFMessage"))
        for i, (stamp, (p, q)) in enumerate(zip(stamps, poses)):
            pose = T["geometry_msgs/msg/PoseStamped"](
                header=header(store, stamp, "base"),
                pose=T["geometry_msgs/msg/Pose"](
                    position=T["geometry_msgs/msg/Point"](x=p[0], y=p[1], z=p[2]),
                    orientation=T["geometry_msgs/msg/Quaternion"](x=q[0], y=q[1], z=q[2], w=q[3]),
                ),
            )
            writer.write(pose_c, stamp, store.serialize_ros1(pose, "geometry_msgs/msg/PoseStamped"))
            tf = T["tf2_msgs/msg/TFMessage"](transforms=[transform(stamp, "base", "tracker", p, q)])
            writer.write(tf_c, stamp + 1000, store.serialize_ros1(tf, "tf2_msgs/msg/TFMessage"))
            if i % 30 == 0:
                button = T["my_msgs/msg/Button"](pressed=i % 60 == 0, label="trigger")
                writer.write(button_c, stamp, store.serialize_ros1(button, "my_msgs/msg/Button"))


def write_types(path, k):
    """Reach k in the other pose types of ROS 1, one topic each."""
    store = typestore()
    T = store.types
    stamps, poses = demo(k)
    path.unlink(missing_ok=True)
    with Writer(path) as writer:
        names = {
            "/cov": "geometry_msgs/msg/PoseWithCovarianceStamped",
            "/point": "geometry_msgs/msg/PointStamped",
            "/transform": "geometry_msgs/msg/TransformStamped",
            "/odom": "nav_msgs/msg/Odometry",
        }
        conns = {t: writer.add_connection(t, m, typestore=store) for t, m in names.items()}
        for stamp, (p, q) in zip(stamps, poses):
            point = T["geometry_msgs/msg/Point"](x=p[0], y=p[1], z=p[2])
            quat = T["geometry_msgs/msg/Quaternion"](x=q[0], y=q[1], z=q[2], w=q[3])
            pose = T["geometry_msgs/msg/Pose"](position=point, orientation=quat)
            cov = T["geometry_msgs/msg/PoseWithCovariance"](pose=pose, covariance=np.eye(6).ravel() * 1e-6)
            twist = T["geometry_msgs/msg/TwistWithCovariance"](
                twist=T["geometry_msgs/msg/Twist"](
                    linear=T["geometry_msgs/msg/Vector3"](x=0.1, y=0.0, z=0.0),
                    angular=T["geometry_msgs/msg/Vector3"](x=0.0, y=0.0, z=0.2),
                ),
                covariance=np.zeros(36),
            )
            messages = {
                "/cov": T["geometry_msgs/msg/PoseWithCovarianceStamped"](header=header(store, stamp, "base"), pose=cov),
                "/point": T["geometry_msgs/msg/PointStamped"](header=header(store, stamp, "base"), point=point),
                "/transform": T["geometry_msgs/msg/TransformStamped"](
                    header=header(store, stamp, "base"),
                    child_frame_id="tracker",
                    transform=T["geometry_msgs/msg/Transform"](
                        translation=T["geometry_msgs/msg/Vector3"](x=p[0], y=p[1], z=p[2]), rotation=quat
                    ),
                ),
                "/odom": T["nav_msgs/msg/Odometry"](
                    header=header(store, stamp, "base"), child_frame_id="tracker", pose=cov, twist=twist
                ),
            }
            for topic, msg in messages.items():
                writer.write(conns[topic], stamp, store.serialize_ros1(msg, names[topic]))


def records(data):
    """(offset, header fields {name: (value offset, value bytes)}, data offset, data length)."""
    pos = 13
    while pos + 4 <= len(data):
        hlen = int.from_bytes(data[pos : pos + 4], "little")
        fields, at = {}, pos + 4
        while at < pos + 4 + hlen:
            flen = int.from_bytes(data[at : at + 4], "little")
            field = data[at + 4 : at + 4 + flen]
            name, _, value = field.partition(b"=")
            fields[name] = (at + 4 + len(name) + 1, value)
            at += 4 + flen
        dlen = int.from_bytes(data[at : at + 4], "little")
        yield pos, fields, at, dlen
        pos = at + 4 + dlen


def killed(src, dst):
    """What `rosbag record` leaves when killed inside a compressed chunk."""
    data = bytearray(src.read_bytes())
    chunks = [r for r in records(bytes(data)) if r[1].get(b"op", (0, b""))[1] == b"\x05"]
    _, fields, dlen_at, _ = chunks[-1]
    size_at = fields[b"size"][0]
    data[size_at : size_at + 4] = (0).to_bytes(4, "little")
    data[dlen_at : dlen_at + 4] = (0).to_bytes(4, "little")
    pos = data.find(b"index_pos=")
    data[pos + 10 : pos + 18] = (0).to_bytes(8, "little")
    dst.write_bytes(bytes(data[: dlen_at + 4 + 700]))


def main():
    compressions = ["none", "bz2", "lz4"]
    converted = HERE / "converted"
    for folder in [converted, HERE / "reach", HERE / "odd"]:
        shutil.rmtree(folder, ignore_errors=True)
        folder.mkdir()
    for k, compression in enumerate(compressions, start=1):
        bag = HERE / "reach" / f"reach_{k}.bag"
        write(bag, k, compression)
        subprocess.run(
            [Path(sys.executable).parent / "rosbags-convert", "--src", bag, "--dst", converted / f"reach_{k}", "--dst-storage", "mcap"],
            check=True,
        )
    write_types(HERE / "types.bag", 1)
    # Killed while recording: no index, the last chunk cut short.
    data = (HERE / "reach" / "reach_1.bag").read_bytes()
    body = bytearray(data)
    # The bag header record: header_len, fields..., data_len, padding. Zero
    # its index_pos and cut the file inside its last chunk.
    pos = body.find(b"index_pos=")
    assert pos > 0
    index_pos = int.from_bytes(body[pos + 10 : pos + 18], "little")
    body[pos + 10 : pos + 18] = (0).to_bytes(8, "little")
    last_chunk = body.rfind(b"compression=none", 0, index_pos)
    (HERE / "odd" / "unindexed.bag").write_bytes(bytes(body[: last_chunk + 600]))
    killed(HERE / "reach" / "reach_3.bag", HERE / "odd" / "killed_lz4.bag")
    # Corrupt: bytes in the middle of the first lz4 chunk flipped.
    data = bytearray((HERE / "reach" / "reach_3.bag").read_bytes())
    first = data.find(b"compression=lz4")
    for i in range(first + 200, first + 260):
        data[i] ^= 0x5A
    (HERE / "odd" / "corrupt.bag").write_bytes(bytes(data))


if __name__ == "__main__":
    main()

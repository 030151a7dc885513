#!/usr/bin/env python3
"""Writes the ROS 2 bag fixtures of the rosbag tests with independent writers:
the `rosbags` package (sqlite3 schema 4, MCAP uncompressed and zstd, file and message
compression) and `mcap` + `mcap-ros2-support` (MCAP lz4, MCAP unchunked without summary).
Older layouts (Humble schema 3 + metadata v5, Foxy schema 1 + metadata v4) are made by
down-converting a rosbags bag the way those distros lay it out (drop the newer tables and
columns); the messages table and payloads stay as rosbags wrote them.

    .venv/bin/python test/data/bags/make_fixtures.py [--out DIR]

Content: fixture_data.py. The committed fixtures were made by this script; the tests also
run it at test time into a temporary folder when UWBSAR_VENV is set.
"""

import argparse
import pathlib
import shutil
import sqlite3
import sys
import tempfile

from mcap.writer import CompressionType, IndexType, Writer as McapWriter
from mcap_ros2.writer import Writer as McapRos2Writer
from rosbags.highlevel import AnyReader
from rosbags.rosbag2 import CompressionFormat, CompressionMode, StoragePlugin, Writer
from rosbags.typesys import Stores, get_typestore
from ruamel.yaml import YAML

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import fixture_data as fd  # noqa: E402
import fixture_messages as fm  # noqa: E402

TS = get_typestore(Stores.ROS2_HUMBLE)
QOS_V5 = ('- history: 3\n  depth: 0\n  reliability: 1\n  durability: 2\n  deadline:\n'
          '    sec: 9223372036\n    nsec: 854775807\n  lifespan:\n    sec: 9223372036\n'
          '    nsec: 854775807\n  liveliness: 1\n  liveliness_lease_duration:\n'
          '    sec: 9223372036\n    nsec: 854775807\n  avoid_ros_namespace_conventions: false')


def sorted_messages(select=lambda n: True):
    msgs = sorted(fd.all_messages(), key=lambda m: (m[0], m[1]))
    return [m for n, m in enumerate(msgs) if select(n)]


def write_rosbags(path, plugin, version=9, compression=None, select=lambda n: True):
    w = Writer(path, version=version, storage_plugin=plugin)
    if compression:
        w.set_compression(compression, CompressionFormat.ZSTD)
    with w:
        conns = {}
        for t, topic, msgtype, desc in sorted_messages(select):
            if topic not in conns:
                conns[topic] = w.add_connection(topic, msgtype, typestore=TS)
            w.write(conns[topic], t, TS.serialize_cdr(fm.rosbags_message(TS, t, desc), msgtype))


def load_yaml(path):
    return YAML(typ='safe').load(path.read_text())


def dump_yaml(path, data):
    y = YAML(typ='safe')
    y.default_flow_style = False
    with path.open('w') as f:
        y.dump(data, f)


def downgrade(out, name, schema):
    """A rosbags schema-4 bag rewritten as Humble (schema 3) or Foxy (schema 1) lays it out."""
    tmp = out / (name + '_tmp')
    write_rosbags(tmp, StoragePlugin.SQLITE3)
    info = load_yaml(tmp / 'metadata.yaml')['rosbag2_bagfile_information']
    dst = out / name
    dst.mkdir()
    db = dst / f'{name}_0.db3'
    shutil.copy(tmp / info['relative_file_paths'][0], db)
    shutil.rmtree(tmp)
    con = sqlite3.connect(db)
    con.execute('DROP TABLE message_definitions')
    con.execute('ALTER TABLE topics DROP COLUMN type_description_hash')
    con.execute('UPDATE topics SET offered_qos_profiles = ?', (QOS_V5,))
    if schema == 3:
        con.execute("UPDATE schema SET schema_version = 3, ros_distro = 'humble'")
        con.execute('DELETE FROM metadata')
    else:
        con.execute('DROP TABLE schema')
        con.execute('DROP TABLE metadata')
    con.commit()
    con.execute('VACUUM')
    con.close()
    topics = [{'topic_metadata': {'name': t['topic_metadata']['name'],
                                  'type': t['topic_metadata']['type'],
                                  'serialization_format': 'cdr',
                                  'offered_qos_profiles': QOS_V5},
               'message_count': t['message_count']} for t in info['topics_with_message_count']]
    meta = {'version': 5 if schema == 3 else 4,
            'storage_identifier': 'sqlite3',
            # Foxy wrote paths relative to the bag's parent folder.
            'relative_file_paths': [db.name if schema == 3 else f'{name}/{db.name}'],
            'duration': info['duration'], 'starting_time': info['starting_time'],
            'message_count': info['message_count'], 'topics_with_message_count': topics,
            'compression_format': '', 'compression_mode': ''}
    if schema == 3:
        meta['files'] = [{'path': db.name, 'starting_time': info['starting_time'],
                          'duration': info['duration'], 'message_count': info['message_count']}]
    dump_yaml(dst / 'metadata.yaml', {'rosbag2_bagfile_information': meta})


def write_split(out, name):
    """Two storage files whose messages interleave in time (even and odd messages)."""
    dst = out / name
    dst.mkdir()
    metas = []
    for part in range(2):
        tmp = out / f'{name}_part{part}'
        write_rosbags(tmp, StoragePlugin.SQLITE3, select=lambda n, p=part: n % 2 == p)
        info = load_yaml(tmp / 'metadata.yaml')['rosbag2_bagfile_information']
        shutil.copy(tmp / info['relative_file_paths'][0], dst / f'{name}_{part}.db3')
        shutil.rmtree(tmp)
        metas.append(info)
    counts = {}
    for info in metas:
        for t in info['topics_with_message_count']:
            key = t['topic_metadata']['name']
            counts.setdefault(key, [t['topic_metadata'], 0])[1] += t['message_count']
    start = min(m['starting_time']['nanoseconds_since_epoch'] for m in metas)
    end = max(m['starting_time']['nanoseconds_since_epoch'] + m['duration']['nanoseconds']
              for m in metas)
    meta = dict(metas[0])
    meta['relative_file_paths'] = [f'{name}_0.db3', f'{name}_1.db3']
    meta['files'] = [dict(f, path=f'{name}_{p}.db3') for p, m in enumerate(metas)
                     for f in m['files']]
    meta['starting_time'] = {'nanoseconds_since_epoch': start}
    meta['duration'] = {'nanoseconds': end - start}
    meta['message_count'] = sum(m['message_count'] for m in metas)
    meta['topics_with_message_count'] = [{'topic_metadata': tm, 'message_count': n}
                                         for tm, n in counts.values()]
    dump_yaml(dst / 'metadata.yaml', {'rosbag2_bagfile_information': meta})


def write_mcap_lz4(path):
    with path.open('wb') as f:
        w = McapRos2Writer(f, chunk_size=4096, compression=CompressionType.LZ4)
        schemas = {}
        for t, topic, msgtype, desc in sorted_messages():
            if msgtype not in schemas:
                msgdef, _ = TS.generate_msgdef(msgtype, ros_version=2)
                schemas[msgtype] = w.register_msgdef(msgtype, msgdef)
            w.write_message(topic, schemas[msgtype], fm.dict_message(t, desc), log_time=t,
                            publish_time=t)
        w.finish()


def write_mcap_unchunked(path):
    with path.open('wb') as f:
        w = McapWriter(f, use_chunking=False, index_types=IndexType.NONE, repeat_channels=False,
                       repeat_schemas=False, use_statistics=False, use_summary_offsets=False)
        w.start(profile='ros2', library='make_fixtures.py')
        channels = {}
        for t, topic, msgtype, desc in sorted_messages():
            if topic not in channels:
                msgdef, _ = TS.generate_msgdef(msgtype, ros_version=2)
                schema = w.register_schema(msgtype, 'ros2msg', msgdef.encode())
                channels[topic] = w.register_channel(topic, 'cdr', schema)
            w.add_message(channels[topic], log_time=t, publish_time=t, sequence=0,
                          data=TS.serialize_cdr(fm.rosbags_message(TS, t, desc), msgtype))
        w.finish()


def check(path):
    """Reads a fixture back with rosbags' reader: everything we ship must be readable."""
    if path.suffix == '.mcap':
        return
    with AnyReader([path], default_typestore=TS) as reader:
        n = sum(1 for _ in reader.messages())
    assert n == len(fd.all_messages()), (path, n)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('--out', type=pathlib.Path, default=pathlib.Path(__file__).parent)
    args = parser.parse_args()
    out = args.out
    out.mkdir(parents=True, exist_ok=True)
    names = ['jazzy_sqlite3', 'humble_sqlite3', 'foxy_sqlite3', 'split_sqlite3',
             'sqlite3_file_zstd', 'sqlite3_message_zstd', 'mcap_none', 'mcap_zstd',
             'mcap_lz4.mcap', 'mcap_unchunked.mcap']
    for name in names:
        p = out / name
        if p.is_dir():
            shutil.rmtree(p)
        elif p.exists():
            p.unlink()
    write_rosbags(out / 'jazzy_sqlite3', StoragePlugin.SQLITE3)
    downgrade(out, 'humble_sqlite3', 3)
    downgrade(out, 'foxy_sqlite3', 1)
    write_split(out, 'split_sqlite3')
    write_rosbags(out / 'sqlite3_file_zstd', StoragePlugin.SQLITE3, compression=CompressionMode.FILE)
    write_rosbags(out / 'sqlite3_message_zstd', StoragePlugin.SQLITE3,
                  compression=CompressionMode.MESSAGE)
    write_rosbags(out / 'mcap_none', StoragePlugin.MCAP, version=8)
    write_rosbags(out / 'mcap_zstd', StoragePlugin.MCAP, compression=CompressionMode.STORAGE)
    write_mcap_lz4(out / 'mcap_lz4.mcap')
    write_mcap_unchunked(out / 'mcap_unchunked.mcap')
    for name in names:
        if name != 'foxy_sqlite3':  # rosbags reads Foxy paths relative to the bag itself
            check(out / name)
    print(f'wrote {len(names)} fixtures to {out}')


if __name__ == '__main__':
    main()

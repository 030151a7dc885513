"""Builds the messages of fixture_data.py as `rosbags` objects and as plain dicts
(for the `mcap-ros2-support` encoder)."""

import numpy as np

import fixture_data as fd


def _header(ts, t, frame):
    sec, nsec = fd.split_stamp(t)
    Time = ts.types['builtin_interfaces/msg/Time']
    Header = ts.types['std_msgs/msg/Header']
    return Header(stamp=Time(sec=sec, nanosec=nsec), frame_id=frame)


def _odometry(ts, t, pose, cov, twist):
    m = ts.types
    x, y, yaw = pose
    qx, qy, qz, qw = fd.quaternion_from_yaw(yaw)
    return m['nav_msgs/msg/Odometry'](
        header=_header(ts, t, 'odom'),
        child_frame_id='base_link',
        pose=m['geometry_msgs/msg/PoseWithCovariance'](
            pose=m['geometry_msgs/msg/Pose'](
                position=m['geometry_msgs/msg/Point'](x=x, y=y, z=0.0),
                orientation=m['geometry_msgs/msg/Quaternion'](x=qx, y=qy, z=qz, w=qw)),
            covariance=np.array(cov, dtype=np.float64)),
        twist=m['geometry_msgs/msg/TwistWithCovariance'](
            twist=m['geometry_msgs/msg/Twist'](
                linear=m['geometry_msgs/msg/Vector3'](x=twist[0], y=0.0, z=0.0),
                angular=m['geometry_msgs/msg/Vector3'](x=0.0, y=0.0, z=twist[1])),
            covariance=np.zeros(36, dtype=np.float64)))


def rosbags_message(ts, t, desc):
    m = ts.types
    kind = desc[0]
    if kind == 'radar':
        _, s, k = desc
        layout = m['std_msgs/msg/MultiArrayLayout'](
            dim=[m['std_msgs/msg/MultiArrayDimension'](label='samples', size=fd.NUM_SAMPLES,
                                                       stride=fd.NUM_SAMPLES)],
            data_offset=0)
        return m['std_msgs/msg/Float32MultiArray'](
            layout=layout, data=np.array(fd.radar_samples(s, k), dtype=np.float32))
    if kind == 'odom':
        i = desc[1]
        return _odometry(ts, t, fd.odom_pose(i), fd.odom_covariance(i), (0.25, 0.1 * (i % 3)))
    if kind == 'gt':
        j = desc[1]
        return _odometry(ts, t, fd.ground_truth_pose(j), [0.0] * 36, (0.0, 0.0))
    if kind == 'laser':
        j = desc[1]
        return m['sensor_msgs/msg/LaserScan'](
            header=_header(ts, t, 'laser'), angle_min=-1.5, angle_max=1.5, angle_increment=0.1875,
            time_increment=0.0, scan_time=0.1, range_min=0.25, range_max=8.0,
            ranges=np.array(fd.laser_ranges(j), dtype=np.float32),
            intensities=np.array(fd.laser_intensities(j), dtype=np.float32))
    if kind == 'tf':
        j = desc[1]
        transforms = []
        for n, child in enumerate(['base_link', 'radar_left']):
            qx, qy, qz, qw = fd.quaternion_from_yaw(0.5 * n + j)
            transforms.append(m['geometry_msgs/msg/TransformStamped'](
                header=_header(ts, t, 'odom' if n == 0 else 'base_link'), child_frame_id=child,
                transform=m['geometry_msgs/msg/Transform'](
                    translation=m['geometry_msgs/msg/Vector3'](x=1.0 * j, y=0.18 * n, z=0.0),
                    rotation=m['geometry_msgs/msg/Quaternion'](x=qx, y=qy, z=qz, w=qw))))
        return m['tf2_msgs/msg/TFMessage'](transforms=transforms)
    if kind == 'chatter':
        return m['std_msgs/msg/String'](data=f'hello {desc[1]}')
    raise ValueError(desc)


def dict_message(t, desc):
    """The same message as nested dicts for mcap_ros2's dynamic encoder."""
    def header(frame):
        sec, nsec = fd.split_stamp(t)
        return {'stamp': {'sec': sec, 'nanosec': nsec}, 'frame_id': frame}

    def odometry(pose, cov, twist):
        x, y, yaw = pose
        qx, qy, qz, qw = fd.quaternion_from_yaw(yaw)
        return {'header': header('odom'), 'child_frame_id': 'base_link',
                'pose': {'pose': {'position': {'x': x, 'y': y, 'z': 0.0},
                                  'orientation': {'x': qx, 'y': qy, 'z': qz, 'w': qw}},
                         'covariance': cov},
                'twist': {'twist': {'linear': {'x': twist[0], 'y': 0.0, 'z': 0.0},
                                    'angular': {'x': 0.0, 'y': 0.0, 'z': twist[1]}},
                          'covariance': [0.0] * 36}}

    kind = desc[0]
    if kind == 'radar':
        _, s, k = desc
        return {'layout': {'dim': [{'label': 'samples', 'size': fd.NUM_SAMPLES,
                                    'stride': fd.NUM_SAMPLES}], 'data_offset': 0},
                'data': fd.radar_samples(s, k)}
    if kind == 'odom':
        i = desc[1]
        return odometry(fd.odom_pose(i), fd.odom_covariance(i), (0.25, 0.1 * (i % 3)))
    if kind == 'gt':
        return odometry(fd.ground_truth_pose(desc[1]), [0.0] * 36, (0.0, 0.0))
    if kind == 'laser':
        j = desc[1]
        return {'header': header('laser'), 'angle_min': -1.5, 'angle_max': 1.5,
                'angle_increment': 0.1875, 'time_increment': 0.0, 'scan_time': 0.1,
                'range_min': 0.25, 'range_max': 8.0, 'ranges': fd.laser_ranges(j),
                'intensities': fd.laser_intensities(j)}
    if kind == 'tf':
        j = desc[1]
        transforms = []
        for n, child in enumerate(['base_link', 'radar_left']):
            qx, qy, qz, qw = fd.quaternion_from_yaw(0.5 * n + j)
            transforms.append({'header': header('odom' if n == 0 else 'base_link'),
                               'child_frame_id': child,
                               'transform': {'translation': {'x': 1.0 * j, 'y': 0.18 * n, 'z': 0.0},
                                             'rotation': {'x': qx, 'y': qy, 'z': qz, 'w': qw}}})
        return {'transforms': transforms}
    if kind == 'chatter':
        return {'data': f'hello {desc[1]}'}
    raise ValueError(desc)

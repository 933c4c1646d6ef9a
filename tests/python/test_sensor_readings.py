"""Sensor readings from Python: the IMU's accelerometer and gyroscope."""

import numpy as np

import mrsim


def imu_snake():
    """A chain whose sensor modules carry an IMU each (<imu/> added)."""
    xml = mrsim.Scenario.chain(modules=3, sensors="between",
                               force_sensors=False).to_xml()
    assert "</SensorModule>" in xml
    xml = xml.replace("</SensorModule>", "<imu/></SensorModule>")
    return mrsim.Scenario.from_xml(xml, name="imu_snake")


def test_imu_at_rest_reads_gravity_and_no_rate():
    sim = mrsim.Simulation(imu_snake())
    sim.step(400)  # settled on the ground
    s = sim.state()
    accel, gyro = s.imu_accel, s.imu_gyro
    assert accel.shape == (len(s.sensor_pose), 3)
    assert gyro.shape == accel.shape
    assert not np.isnan(accel).any()
    # Specific force in the module's axes: +g along its up (z), lying flat.
    np.testing.assert_allclose(np.linalg.norm(accel, axis=1), 9.81,
                               atol=0.2)
    np.testing.assert_allclose(accel[:, 2], 9.81, atol=0.3)
    np.testing.assert_allclose(gyro, 0.0, atol=0.05)


def test_imu_readings_are_in_arrays_and_sensor_readings():
    sim = mrsim.Simulation(imu_snake())
    sim.step(10)
    s = sim.state()
    arrays = s.arrays()
    assert np.array_equal(arrays["imu_accel"], s.imu_accel)
    assert np.array_equal(arrays["imu_gyro"], s.imu_gyro)
    readings = s.sensor_readings
    assert len(readings) == len(s.sensor_pose)
    for k, by_kind in enumerate(readings):
        imu = by_kind["imu"]
        assert imu.shape == (1, 6)
        assert np.array_equal(imu[0, :3], s.imu_accel[k])
        assert np.array_equal(imu[0, 3:], s.imu_gyro[k])
    # The logger's columns carry the same values.
    c = s.columns()
    assert c["sensor_module0.imu.accel.z"] == s.imu_accel[0, 2]
    assert c["sensor_module0.imu.gyro.x"] == s.imu_gyro[0, 0]


def test_modules_without_an_imu_read_nan():
    sim = mrsim.Simulation(mrsim.Scenario.chain(modules=3, sensors="between"))
    s = sim.state()
    assert s.imu_accel.shape == (len(s.sensor_pose), 3)
    assert np.isnan(s.imu_accel).all()
    assert np.isnan(s.imu_gyro).all()
    assert all(by_kind == {} for by_kind in s.sensor_readings)

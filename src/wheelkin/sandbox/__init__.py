"""wheelkin.sandbox: every vehicle of the book on wheels, in a 2-D physics world (pymunk).

The sandbox puts a simulated robot beside each chapter's ideal kinematic model, to show where
they agree (everywhere the wheels can grip: to 0.01 mm over 10 m) and where they part (slip,
encoder quantisation, friction limits)::

    from wheelkin.sandbox import World, RADON_ULZER
    world = World(dt=1/240)
    robot = world.add(RADON_ULZER, pose=(0, 0, 0))
    robot.command_twist(0.3, 0.0, 1.0)
    traj = world.run(5.0)           # traj.pose, traj.encoder_counts, traj.slipping ...

Modules: :mod:`.vehicles` (geometry, the four vehicles, ideal wheel commands),
:mod:`.contact` (the friction-limited wheel-ground contact), :mod:`.world` (world, robots,
exact SE(2) stepping, walls), :mod:`.sensors` (encoders), :mod:`.render` (drawings and
animations), :mod:`.runs` (a twist schedule driven open loop, and what its run is compared
with). Everything is SI and REP-103 (x forward, y left, heading counter-clockwise).
"""

try:
    import pymunk  # noqa: F401
except ModuleNotFoundError as exc:  # the formula modules work without it; the sandbox does not
    raise ModuleNotFoundError("wheelkin.sandbox needs pymunk: install the extra, "
                              "pip install \".[sandbox]\" from a checkout") from exc

from .car import RC_CAR, PurePursuitDriver, Steering, car, car_odometry, drive, front_angles
from .vehicles import (
    LAB_ROBOT,
    MECANUM_ROBOT,
    OPEN_SOURCE_ROVER,
    RADON_ULZER,
    VehicleSpec,
    diff_drive,
    ideal_commands,
    mecanum,
    rover,
    skid_steer,
)
from .world import Robot, Trajectory, World

__all__ = [
    "LAB_ROBOT",
    "MECANUM_ROBOT",
    "OPEN_SOURCE_ROVER",
    "RADON_ULZER",
    "RC_CAR",
    "PurePursuitDriver",
    "Robot",
    "Steering",
    "Trajectory",
    "VehicleSpec",
    "World",
    "car",
    "car_odometry",
    "diff_drive",
    "drive",
    "front_angles",
    "ideal_commands",
    "mecanum",
    "rover",
    "skid_steer",
]

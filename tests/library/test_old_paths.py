"""The names that moved out of ``odometry`` and ``frames`` keep their old import paths.

Notebooks and robot builders import ``wheelkin.odometry.propagate_covariance`` and
``wheelkin.frames.firmware_pose_to_ours``; those are the very objects of their new modules,
which are documented once, where they live.
"""

from __future__ import annotations

import importlib

import pytest

MOVED = {
    "odometry_uncertainty": ("odometry", ["PathCovariance", "PoseCovariance", "StepJacobians",
                                          "UmbmarkCorrection", "monte_carlo_poses",
                                          "propagate_covariance", "propagate_path",
                                          "step_jacobians", "umbmark_correction"]),
    "sources": ("frames", ["FirmwarePose", "MecanumDocPose", "MecanumDocTwist",
                           "firmware_pose_to_ours", "lab_pose_to_ours",
                           "mecanum_doc_heading_to_ours", "mecanum_doc_pose_to_ours",
                           "mecanum_doc_twist_to_ours", "ours_to_firmware_pose",
                           "ours_to_lab_pose", "ours_to_mecanum_doc_heading",
                           "ours_to_mecanum_doc_pose", "ours_to_mecanum_doc_twist",
                           "ours_to_rover_radius", "rover_radius_to_ours", "rover_twist"]),
}


@pytest.mark.parametrize("new", sorted(MOVED))
def test_moved_names_keep_their_old_import_path(new):
    old, names = MOVED[new]
    new_mod = importlib.import_module(f"wheelkin.{new}")
    old_mod = importlib.import_module(f"wheelkin.{old}")
    assert sorted(new_mod.__all__) == sorted(names)  # the whole new module is reachable
    for name in names:
        assert getattr(old_mod, name) is getattr(new_mod, name), name
        assert getattr(new_mod, name).__module__ == new_mod.__name__, name
        assert name not in old_mod.__all__  # documented once, where it lives


def test_pose_and_twist_carry_their_public_home():
    from wheelkin import frames

    assert frames.Pose.__module__ == frames.Twist.__module__ == "wheelkin.frames"

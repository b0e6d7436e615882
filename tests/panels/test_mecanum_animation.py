"""The mecanum chapter's kernel-free animation (wheelkin.widgets.mecanum.animate_poses)."""

from __future__ import annotations

import numpy as np
import pytest

from wheelkin.animation import to_html
from wheelkin.mecanum import MecanumGeometry
from wheelkin.widgets.mecanum import animate_poses

GEOMETRY = MecanumGeometry(half_wheelbase=0.2, half_track=0.2, wheel_radius=0.05)
# A 2 m straight run east, then north: 41 poses.
POSES = np.array([(min(s, 2.0), max(s - 2.0, 0.0), 0.0) for s in np.linspace(0, 4, 41)])


def test_an_outside_legend_lies_right_of_the_axes_within_the_figure():
    anim = animate_poses(GEOMETRY, POSES, plan=POSES[:, :2], frames_count=3, legend="outside")
    to_html(anim, name="test-mecanum-outside", alt="a mecanum vehicle")
    fig = anim._fig
    ax = fig.axes[0]
    box = ax.get_legend().get_window_extent()
    assert box.x0 > ax.get_window_extent().x1
    assert box.x1 <= fig.bbox.x1


def test_the_interval_is_the_players_and_bad_options_are_refused():
    anim = animate_poses(GEOMETRY, POSES, frames_count=3, interval=250.0)
    html = to_html(anim, name="test-mecanum-interval", alt="a mecanum vehicle")
    assert ", 250.0," in html  # the player's frame interval, ms
    with pytest.raises(ValueError, match="legend must be one of"):
        animate_poses(GEOMETRY, POSES, legend="lower left")
    with pytest.raises(ValueError, match="interval"):
        animate_poses(GEOMETRY, POSES, interval=0.0)

"""Drawings and animations of the sandbox's vehicles."""

from __future__ import annotations

import math

import matplotlib.pyplot as plt
import numpy as np
import pytest
from matplotlib.colors import to_hex
from matplotlib.figure import Figure

from wheelkin import style
from wheelkin.animation import to_html
from wheelkin.sandbox import (
    LAB_ROBOT,
    MECANUM_ROBOT,
    OPEN_SOURCE_ROVER,
    RADON_ULZER,
    World,
    ideal_commands,
)
from wheelkin.sandbox.render import (
    SLIP_COLOUR,
    WHEEL_COLOUR,
    SandboxAnimation,
    animate,
    draw_vehicle,
)


def axes():
    ax = Figure().add_subplot()
    ax.set_aspect("equal")
    return ax


def to_world(pose, p):
    x, y, th = pose
    return (x + math.cos(th) * p[0] - math.sin(th) * p[1],
            y + math.sin(th) * p[0] + math.cos(th) * p[1])


def test_body_and_wheels_are_drawn_at_the_pose():
    pose = (1.0, -2.0, 0.7)
    drawing = draw_vehicle(axes(), LAB_ROBOT, pose)
    expected = [to_world(pose, p) for p in LAB_ROBOT.body]
    np.testing.assert_allclose(drawing.body.get_xy()[:4], expected, atol=1e-12)
    for wheel, patch in zip(LAB_ROBOT.wheels, drawing.wheels, strict=True):
        centre = patch.get_xy()[:4].mean(0)
        np.testing.assert_allclose(centre, to_world(pose, wheel.position), atol=1e-12)


def test_steered_wheels_turn_by_their_steering_angle():
    steer = [0.3, -0.2, -0.3, 0.2]  # LF, RF, LB, RB
    pose = (0.0, 0.0, 0.5)
    drawing = draw_vehicle(axes(), OPEN_SOURCE_ROVER, pose, steer)
    angles = dict(zip(OPEN_SOURCE_ROVER.steered_names, steer, strict=True))
    for wheel, patch in zip(OPEN_SOURCE_ROVER.wheels, drawing.wheels, strict=True):
        xy = patch.get_xy()
        along = xy[1] - xy[0]  # the tyre's long side
        direction = math.atan2(along[1], along[0])
        assert direction == pytest.approx(0.5 + angles.get(wheel.name, 0.0), abs=1e-12)


def test_icr_is_marked_where_the_twist_turns_about():
    pose = (1.0, 2.0, math.pi / 2)
    drawing = draw_vehicle(axes(), RADON_ULZER, pose, show_icr=True, twist=(0.2, 0.0, 1.0))
    x, y = drawing.icr.get_data()
    # Body-frame ICR (0, v / omega) = (0, 0.2), turned by 90 deg: (-0.2, 0) from (1, 2).
    assert (x[0], y[0]) == pytest.approx((0.8, 2.0))
    assert len(drawing.icr_lines.get_segments()) == 2
    drawing.update(pose, twist=(0.2, 0.0, 0.0))  # straight: no ICR
    assert len(drawing.icr.get_data()[0]) == 0


def test_rover_icr_lines_are_perpendicular_to_the_steered_wheels():
    twist = (0.3, 0.0, 0.5)
    _, steer = ideal_commands(OPEN_SOURCE_ROVER, twist)
    drawing = draw_vehicle(axes(), OPEN_SOURCE_ROVER, (0, 0, 0), steer, show_icr=True,
                           twist=twist)
    icr = np.array([c[0] for c in drawing.icr.get_data()])
    for wheel, patch in zip(OPEN_SOURCE_ROVER.wheels, drawing.wheels, strict=True):
        xy = patch.get_xy()
        along = (xy[1] - xy[0]) / np.linalg.norm(xy[1] - xy[0])
        radial = np.array(wheel.position) - icr
        assert abs(along @ radial) < 1e-12


def test_slipping_wheels_are_red():
    drawing = draw_vehicle(axes(), LAB_ROBOT, (0, 0, 0), slipping=[True, False, False, True])
    colours = [to_hex(p.get_facecolor()) for p in drawing.wheels]
    assert colours == [SLIP_COLOUR, WHEEL_COLOUR, WHEEL_COLOUR, SLIP_COLOUR]
    with pytest.raises(ValueError, match="slipping"):
        drawing.update((0, 0, 0), slipping=[True])


def test_mecanum_ground_rollers_form_an_x():
    drawing = draw_vehicle(axes(), MECANUM_ROBOT, (0, 0, 0))
    segs = np.array(drawing.rollers.get_segments()).reshape(4, 4, 2, 2)  # wheel, roller
    slopes = [(s[0, 1, 1] - s[0, 0, 1]) / (s[0, 1, 0] - s[0, 0, 0]) for s in segs]
    # FL and RR along (1, -1), FR and RL along (1, 1): an X seen from above.
    np.testing.assert_allclose(slopes, [-1, 1, 1, -1], atol=1e-12)


def test_bad_pose_is_refused():
    with pytest.raises(ValueError, match="pose"):
        draw_vehicle(axes(), LAB_ROBOT, (0, float("nan"), 0))
    with pytest.raises(ValueError, match="spec"):
        draw_vehicle(axes(), "lab robot", (0, 0, 0))


@pytest.fixture(scope="module")
def two_runs():
    world = World()
    world.add(RADON_ULZER, twist=(0.2, 0.0, 1.0))
    world.add(RADON_ULZER.replace(mu=0.05), pose=(0.0, 0.4, 0.0))
    world.robots[1].command_twist(0.2, 0.0, 1.0)
    return world.run(1.0, record_every=6)


def test_animation_is_small_deterministic_and_has_the_frames(two_runs):
    html = []
    for _ in range(2):
        anim = animate(two_runs, [RADON_ULZER, RADON_ULZER.replace(mu=0.05)], frames=6,
                       show_icr=True, plan=[(0, 0), (0.2, 0.2)],
                       extra_paths={"estimate": two_runs[0].pose[:, :2] + 0.01},
                       walls=[((-0.2, -0.2), (0.5, -0.2))], title="two robots")
        assert isinstance(anim, SandboxAnimation)
        html.append(to_html(anim, name="test-two", alt="two robots turning"))
    assert html[0] == html[1]
    assert html[0].count("data:image/png;base64") == 6
    assert len(html[0]) < 150_000


def test_animation_inputs_are_checked(two_runs):
    with pytest.raises(ValueError, match="frames"):
        animate(two_runs[0], RADON_ULZER, frames=1)
    with pytest.raises(ValueError, match="spec"):
        animate(two_runs, RADON_ULZER)
    with pytest.raises(ValueError, match="extra_paths"):
        animate(two_runs[0], RADON_ULZER, extra_paths={"bad": [1, 2, 3]})
    with pytest.raises(ValueError, match="colors"):
        animate(two_runs[0], RADON_ULZER, colors=1000)
    with pytest.raises(ValueError, match="legend must be one of"):
        animate(two_runs[0], RADON_ULZER, plan=[(0, 0), (1, 0)], legend="top")
    for bad in (0.0, -1.0, 1.5, math.nan):  # the run lasts 1 s
        with pytest.raises(ValueError, match="until"):
            animate(two_runs[0], RADON_ULZER, until=bad)


def test_an_outside_legend_lies_right_of_the_axes_and_covers_nothing(two_runs):
    anim = animate(two_runs[0], RADON_ULZER, frames=3, plan=[(0, 0), (0.2, 0.2)],
                   legend="outside")
    to_html(anim, name="test-outside", alt="a robot turning")
    fig = anim._fig
    ax = fig.axes[0]
    box = ax.get_legend().get_window_extent()
    assert box.x0 > ax.get_window_extent().x1
    assert box.x1 <= fig.bbox.x1


def test_until_ends_the_frames_at_that_time(two_runs):
    # 5 frames over 0..0.5 s of a 1 s run: the last shows t = 0.50 s and the vehicle there.
    anim = animate(two_runs[0], RADON_ULZER, frames=5, until=0.5)
    to_html(anim, name="test-until", alt="a robot turning")  # ends on the last frame
    stamp = next(t for t in anim._fig.axes[0].texts if t.get_text().startswith("t ="))
    assert stamp.get_text() == "t =  0.50 s"
    run = two_runs[0]
    i = int(np.searchsorted(run.t, 0.5 - 1e-12))
    point = anim._fig.axes[0].lines
    xs = [line.get_xdata() for line in point if len(line.get_xdata()) == 1
          and line.get_marker() == "o"]
    assert xs and math.isclose(float(xs[0][0]), run.pose[i, 0])


def test_slip_panel_redraws_at_every_slider_extreme_without_raising():
    from wheelkin.widgets import all_panels, slider_values

    panel = all_panels()["sandbox.slip"]()
    try:
        for mu in slider_values(panel.controls["mu"], 3):
            for omega in slider_values(panel.controls["omega"], 3):
                panel.redraw(mu=mu, omega=omega)
        view = panel.state
        # On a good floor a gentle turn stays on the model; on ice a sharp one does not.
        panel.redraw(mu=1.0, omega=1.0)
        assert "off the model by 0.0 cm" in view.title.get_text()
        panel.redraw(mu=0.05, omega=6.0)
        assert len(view.slips.get_data()[0]) > 0
    finally:
        panel.close()


def test_slip_panel_blits_the_picture_of_a_full_draw():
    import io

    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from PIL import Image

    from wheelkin.sandbox.vehicles import GRAVITY
    from wheelkin.widgets import all_panels
    from wheelkin.widgets.sandbox import SlipView

    panel = all_panels()["sandbox.slip"]()
    try:
        assert panel._blit  # the panel blits
        for mu, omega in ((0.8, 2.0), (0.05, 6.0), (1.0, 0.0), (0.3, 4.0), (0.8, 2.0)):
            panel.redraw(mu=mu, omega=omega)
            blitted = np.asarray(Image.open(io.BytesIO(panel.image.value)))
            with plt.rc_context(style._RC):  # a fresh figure drawn whole, in the book's style
                fig = Figure(figsize=(6.0, 4.6), dpi=100, layout="none")
                FigureCanvasAgg(fig)
                SlipView(fig).update(mu, omega)
                fig.canvas.draw()
            np.testing.assert_array_equal(blitted, np.asarray(fig.canvas.buffer_rgba()))
            assert f"grip ≤ {mu * GRAVITY:.2f}" in panel.state.title.get_text()  # tracks only
    finally:
        panel.close()

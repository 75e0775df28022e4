"""LinearModel.preloads against the statics done by hand: the double pendulum's pins carry
the weight below them, the half car's axles share the weight by the lever rule."""

import pytest

import eom
from conftest import ROOT


def test_double_pendulum_pins_carry_the_weight_below():
    m1, m2, g = 2.0, 3.0, 9.81
    lin = eom.load(str(ROOT / "models" / "double_pendulum.toml")).linearize(m1=m1, m2=m2, g=g)
    p = lin.preloads
    assert p.statics == "determinate"
    pin1, pin2 = p["pin1"], p["rigid point `pin2`"]
    assert (pin1.body, pin2.body) == ("rod1", "rod2")
    # The force on the pinned rod, up (+z): everything it holds.
    assert pin1.force == pytest.approx((0.0, 0.0, (m1 + m2) * g), rel=1e-12, abs=1e-12)
    assert pin2.force == pytest.approx((0.0, 0.0, m2 * g), rel=1e-12, abs=1e-12)
    assert pin1.moment == (0.0, 0.0, 0.0)
    assert pin1.unique and pin1.computed and pin1.tension is None


def test_half_car_lever_rule():
    m, a, b, g = 1350.0, 1.1, 1.5, 9.81
    lin = eom.load(str(ROOT / "models" / "half_car.toml")).linearize(m=m, a=a, b=b, g=g)
    p = lin.preloads
    front, rear = p["front suspension"], p["rear suspension"]
    # Each axle carries the weight in proportion to the other's distance from the mass centre.
    assert front.force[2] == pytest.approx(m * g * b / (a + b), rel=1e-12)
    assert rear.force[2] == pytest.approx(m * g * a / (a + b), rel=1e-12)
    # Springs in compression: negative tension.
    assert front.tension == pytest.approx(-m * g * b / (a + b), rel=1e-12)
    assert [x.item for x in p.items][:2] == ["rigid point `no surge or sway`",
                                             "rigid point `no roll or yaw`"]


def test_unloaded_model_and_pickled_linear_model():
    import pickle

    lin = eom.load("smd").linearize()
    assert lin.preloads.statics == "unloaded"
    assert all(x.force == (0.0, 0.0, 0.0) for x in lin.preloads.items)
    with pytest.raises(KeyError, match="no preload of `nope`"):
        lin.preloads["nope"]
    dp = eom.load(str(ROOT / "models" / "double_pendulum.toml")).linearize(m2=4.0)
    again = pickle.loads(pickle.dumps(dp))
    assert again.preloads == dp.preloads

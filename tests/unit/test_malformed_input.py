"""Malformed input is refused before anything is built, with one line naming what is wrong.

Each input goes the way the command line takes it: parameters read (load_case), then the
case prepared (prepare: bristles' reach, slide CSV), and nothing solved.

Each row is (kind, input, part of the message it must produce). Kinds: ``set`` --set
overrides on the orthogonal case; ``toml`` the text of a case file; ``csv`` the text of a
slide-profile CSV used by the case; ``case`` the CASE argument itself.
"""

import os

import pytest

from exubrush.parameters.fields import ParameterError
from exubrush.parameters.io import load_case
from exubrush.run.prepared import prepare

MALFORMED = [
    # lengths, moduli and other positive quantities
    ("set", ["head.bristle.length='-1 mm'"], "head.bristle.length: -1 mm must be > 0 mm"),
    ("set", ["head.bristle.length='0 mm'"], "head.bristle.length: 0 mm must be > 0 mm"),
    ("set", ["head.bristle.tip_radius='0 mm'"], "head.bristle.tip_radius: 0 mm must be > 0 mm"),
    ("set", ["head.material.youngs_modulus='0 MPa'"], "youngs_modulus: 0 MPa must be > 0 MPa"),
    ("set", ["head.material.density='-1 kg/m^3'"], "density: -1 kg/m^3 must be > 0 kg/m^3"),
    ("set", ["head.material.damping_time='-1 s'"], "damping_time: -1 s must be >= 0 s"),
    ("set", ["head.pitch_along='-1 mm'"], "head.pitch_along: -1 mm must be > 0 mm"),
    ("set", ["head.rows=0"], "head.rows: 0 must be > 0"),
    ("set", ["model.segments=0"], "model.segments: 0 must be > 0"),
    ("set", ["motion.periods=-1"], "motion.periods: -1 must be > 0"),
    ("set", ["motion.approach_duration='0 s'"], "approach_duration: 0 s must be > 0 s"),
    ("set", ["motion.hold_duration='-1 s'"], "hold_duration: -1 s must be >= 0 s"),
    ("set", ["solver.step_size='0 s'"], "solver.step_size: 0 s must be > 0 ms"),
    ("set", ["output.interval='0 s'"], "output.interval: 0 s must be > 0 s"),
    # material and contact ranges
    ("set", ["head.material.poisson_ratio=0.5"], "poisson_ratio: 0.5 must be < 0.5"),
    ("set", ["head.material.poisson_ratio=-0.1"], "poisson_ratio: -0.1 must be >= 0"),
    ("set", ["contact.dynamic_friction=-0.2"], "contact.dynamic_friction: -0.2 must be >= 0"),
    ("set", ["contact.static_velocity='2 mm/s'"], "static_velocity (2 mm/s) must be below"),
    ("set", ["contact.stiffness_exponent=0"], "contact.stiffness_exponent: 0 must be > 0"),
    ("set", ["model.prb_gamma=1.5"], "model.prb_gamma: 1.5 must be < 1"),
    ("set", ["head.root_tilt='100 deg'"], "head.root_tilt: 100 deg must be < 30 deg"),
    ("set", ["solver.spectral_radius=1.5"], "spectral_radius 1.5 must be <= 1"),
    ("set", ["solver.minimum_step_size='1 s'"], "minimum_step_size must not exceed step_size"),
    ("set", ["solver.threads=0"], "solver.threads: 0 must be >= 1"),
    ("set", ["solver.force_tolerance=-1"], "solver.force_tolerance: -1 must be >= 0"),
    ("set", ["solver.force_tolerance=0.5"], "solver.force_tolerance: 0.5 must be < 0.01"),
    ("set", ["solver.sliding_step_factor=0.5"], "solver.sliding_step_factor: 0.5 must be >= 1"),
    ("set", ["solver.touching_give_up=1"], "solver.touching_give_up: 1 must be < 1"),
    ("set", ["solver.touching_give_up=-0.1"], "solver.touching_give_up: -0.1 must be >= 0"),
    ("set", ["solver.touching_give_up=nan"], "solver.touching_give_up: nan is not a finite number"),
    ("set", ["solver.sliding_speed_fraction=1.5"],
     "solver.sliding_speed_fraction: 1.5 must be < 1"),
    ("set", ["solver.threads=2"], "threads = 2 needs partition 'coupled'"),
    ("set", ["solver.threads=2", "solver.partition='coupled'"],
     "solver.threads = 2 needs contact.backend 'exudyn-builtin'"),
    # surfaces
    ("set", ["surface.kind='cone'"], "surface.kind: 'cone' is not one of 'plane', 'cylinder'"),
    ("set", ["surface.kind='tooth-row'", "surface.edge_radius='4 mm'"],
     "edge_radius (4 mm) must be below half the tooth_width (7 mm)"),
    ("set", ["surface.kind='tooth-row'", "surface.gap_depth='0.2 mm'"],
     "edge_radius (0.5 mm) must not exceed gap_depth (0.2 mm)"),
    ("set", ["surface.radius='-3 mm'"], "surface.radius: -3 mm must be > 0 mm"),
    ("set", ["surface.radius='1e12 mm'"], "surface.radius: 1e12 mm must be < 1e+06 mm"),
    ("set", ["surface.kind='cylinder'", "contact.backend='exudyn-builtin'"],
     "contact.backend 'exudyn-builtin' brushes a plane only"),
    ("set", ["surface.kind='sphere'", "surface.x='60 mm'"],
     "surface: no bristle can reach the sphere at x = 60 mm"),
    ("set", ["surface.yaw=1"], "surface.yaw: 1 has no unit"),
    ("set", ["head.rows=1", "head.columns=1", "head.root_jitter='50 mm'"],
     "head.root_jitter: 50 mm must be < 1 mm"),
    # the stick/slip friction law
    ("set", ["contact.friction_model='coulomb'"],
     "contact.friction_model: 'coulomb' is not one of 'paper', 'stick-slip'"),
    ("set", ["contact.friction_model='stick-slip'", "surface.kind='cylinder'"],
     "contact.friction_model 'stick-slip' is written for the plane"),
    ("set", ["contact.friction_model='stick-slip'", "contact.backend='exudyn-builtin'"],
     "contact.backend 'exudyn-builtin' has its own friction"),
    ("set", ["contact.friction_model='stick-slip'", "contact.static_friction=0"],
     "friction_model 'stick-slip' needs static_friction above 0"),
    ("set", ["contact.stick_stretch='-1 um'"], "contact.stick_stretch: -1 um must be > 0 um"),
    ("set", ["contact.stick_stretch='1 mm'"], "contact.stick_stretch: 1 mm must be < 100 um"),
    ("set", ["contact.stick_stretch=1"], "contact.stick_stretch: 1 has no unit"),
    ("set", ["contact.stick_damping_time='-1 us'"],
     "contact.stick_damping_time: -1 us must be >= 0 us"),
    # renamed keys and real booleans
    ("set", ["solver.user_functions='builtin'"],
     "--set solver.user_functions: renamed contact.backend: 'symbolic' is now 'paper-symbolic'"),
    ("toml", "[solver]\nuser_functions = 'python'\n",
     "solver.user_functions: renamed contact.backend"),
    ("set", ["solver.modified_newton='yes'"],
     "solver.modified_newton: expected true or false, got 'yes'"),
    ("toml", "[output]\nsolution_file = 1\n", "output.solution_file: expected true or false"),
    ("set", ["contact.backend='builtin'"],
     "contact.backend: 'builtin' is not one of 'paper-symbolic', 'paper-python', "
     "'paper-compiled', 'exudyn-builtin'"),
    # units
    ("set", ["head.bristle.length=5"], "head.bristle.length: 5 has no unit"),
    ("set", ["contact.damping='0.2'"], "contact.damping: '0.2' has no unit"),
    ("set", ["head.material.youngs_modulus='5 mm'"], "cannot be converted to 'MPa'"),
    ("set", ["contact.stiffness='100 N/mm'"], "cannot be converted to 'N/mm^1.3'"),
    ("set", ["head.bristle.width='abc'"], "cannot read 'abc' as a quantity"),
    ("set", ["motion.amplitude='nan mm'"], "motion.amplitude: 'nan mm' is not a finite number"),
    # types and choices
    ("set", ["model.kind='beam'"], "model.kind: 'beam' is not one of 'dfm', 'prb'"),
    ("set", ["head.bristle.section='hexagon'"], "'hexagon' is not one of 'rectangle'"),
    ("set", ["model.segments=2.5"], "model.segments: expected a whole number"),
    ("set", ["head.rows='four'"], "head.rows: expected a whole number, got 'four'"),
    ("set", ["name=3"], "name: expected text, got 3"),
    # keys and syntax of --set
    ("set", ["head.bristle.lenght='5 mm'"], "--set head.bristle.lenght: unknown parameter"),
    ("set", ["length='5 mm'"], "did you mean head.bristle.length"),
    ("set", ["head.rows"], "expected KEY=VALUE"),
    # rules across fields
    ("set", ["head.bristle.section='circle'"], "a circle section needs width == height"),
    ("set", ["motion.profile='csv'"], "profile 'csv' needs csv_file"),
    ("set", ["output.shape_interval='0.001 s'"], "shape_interval (0.001 s) must not be shorter"),
    ("set", ["model.kind='prb'", "contact.dynamic_friction=0", "contact.static_friction=0"],
     "'1/mu_d' is infinite for contact.dynamic_friction = 0"),
    ("set", ["model.kind='prb'", "model.prb_load_ratio='-2'"],
     "PRB load ratio n = -2 is outside [0, 10] of model.prb_parameters 'howell-table'"),
    ("set", ["model.kind='prb'", "model.prb_load_ratio='many'"],
     "model.prb_load_ratio 'many' is neither '1/mu_d' nor a number"),
    ("set", ["model.kind='prb'", "motion.hold_duration='0 s'"], "set motion.hold_duration > 0"),
    ("set", ["motion.interaction_distance='10 mm'"], "no bristle would touch"),
    # case files
    ("toml", "[head\nrows = 2\n", "not valid TOML"),
    ("toml", "[head]\nrows = 2\nrows = 3\n", "not valid TOML (Cannot overwrite a value"),
    ("toml", "[head]\ncolour = 'red'\n", "head.colour: unknown key"),
    ("toml", "[colour]\nx = 1\n", "colour: unknown key; known keys here: contact, head"),
    ("toml", "[head]\nbristles = 3\n", "head.bristles: expected a list of tables"),
    ("toml", "[head]\nlayout = 'list'\n", "layout 'list' needs at least one [[head.bristles]]"),
    ("toml", '[head]\nlayout = "list"\n[[head.bristles]]\nx = "0 mm"\ncolour = "red"\n',
     "head.bristles[0].colour: unknown key"),
    ("toml", '[head]\nlayout = "list"\n[[head.bristles]]\nx = "1 mm"\n[[head.bristles]]\n'
     'x = "1 mm"\n', "bristles[1] has the same root (x, y) as bristles[0]"),
    ("toml", '[head.material]\nyoungs_modulus = 7.5\n', "youngs_modulus: 7.5 has no unit"),
    # measured slide profiles
    ("csv", "", "needs a header and at least two rows, found 0 lines"),
    ("csv", "time [s],slider_position [mm]\n", "needs a header and at least two rows"),
    ("csv", "time [s],position [mm]\n0,0\n1,1\n", "has no column 'slider_position [unit]'"),
    ("csv", "time,slider_position [mm]\n0,0\n1,1\n", "column 'time' has no unit"),
    ("csv", "time [mm],slider_position [mm]\n0,0\n1,1\n", "cannot be converted to 's'"),
    ("csv", "time [s],slider_position [mm]\n0,0\n1,abc\n", "line 3, column 'slider_position': "
     "'abc' is not a number"),
    ("csv", "time [s],slider_position [mm]\n0,0\n1\n", "line 3, column 'slider_position'"),
    ("csv", "time [s],slider_position [mm]\n0,0\n1,1\n0.5,2\n",
     "times must increase strictly, but sample 3 is at 0.5 s after 1 s"),
    ("csv", "time [s],slider_position [mm]\n0,0\n1,nan\n", "must hold finite numbers only"),
    # pose terms
    ("set", ["motion.sine=[]"], "motion.sine is a list of tables: give its entries in a case "
     "file as [[motion.sine]]"),
    ("toml", '[[motion.sine]]\naxis = "y"\nfrequency = "260 Hz"\n',
     "motion.sine[0]: axis 'y' needs a amplitude above 0"),
    ("toml", '[[motion.sine]]\naxis = "y"\namplitude = "1 mm"\nfrequency = "inf Hz"\n',
     "motion.sine[0].frequency"),
    ("toml", '[[motion.sine]]\naxis = "y"\namplitude = "1 mm"\nfrequency = "nan Hz"\n',
     "motion.sine[0].frequency"),
    ("toml", '[[motion.sine]]\naxis = "y"\namplitude = "1 mm"\nfrequency = "2 s"\n',
     "motion.sine[0].frequency"),
    ("toml", '[[motion.sine]]\naxis = "y"\namplitude = "1 mm"\nfrequency = 260\n',
     "motion.sine[0].frequency: 260 has no unit"),
    ("toml", '[[motion.sine]]\naxis = "rz"\nangle = "200 deg"\nfrequency = "1 Hz"\n',
     "motion.sine[0].angle"),
    ("toml", '[solver]\nstep_size = "1e-9 s"\n[[motion.sine]]\naxis = "y"\n'
     'amplitude = "1 mm"\nfrequency = "1e9 Hz"\n', "more than Exudyn can count"),
    ("toml", '[[motion.sine]]\naxis = "y"\namplitude = "1 mm"\nfrequency = "10 Hz"\n'
     'start = "1e6 s"\n',
     "motion.sine[0] starts 1e+06 s after the slide, at or after the run's end"),
    ("pose", "time [s],y [mm]\n0,0\n0.1,abc\n", "line 3, column 'y': 'abc' is not a number"),
    ("pose", "time [s],y [deg]\n0,0\n0.1,1\n", "column 'y'"),
    ("pose", "time [s],rz\n0,0\n0.1,1\n", "column 'rz' has no unit"),
    ("pose", "time [s],rz [deg]\n0,0\n0.1,inf\n", "must hold finite numbers only"),
    ("pose", "time [s],colour [mm]\n0,0\n0.1,1\n", "has none of the pose columns"),
    # the CASE argument
    ("case", "diagonal", "unknown case 'diagonal': use orthogonal, parallel"),
    ("case", "missing.toml", "case file 'missing.toml' does not exist"),
]


def _load(kind, given, tmp_path):
    if kind == "set":
        return prepare(load_case("orthogonal", given))
    if kind == "toml":
        path = tmp_path / "case.toml"
        path.write_text(given)
        return prepare(load_case(str(path)))
    if kind == "csv":
        path = tmp_path / "slide.csv"
        path.write_text(given)
        return prepare(load_case("orthogonal", ["motion.profile='csv'",
                                                f"motion.csv_file='{path}'"]))
    if kind == "pose":
        path = tmp_path / "pose.csv"
        path.write_text(given)
        return prepare(load_case("orthogonal", [f"motion.pose_csv='{path}'",
                                                "solver.step_size='0.5 ms'"]))
    return prepare(load_case(given))


@pytest.mark.parametrize("kind, given, message", MALFORMED)
def test_malformed_input_is_refused_with_its_message(kind, given, message, tmp_path):
    with pytest.raises(ParameterError) as info:
        _load(kind, given, tmp_path)
    assert message in str(info.value)
    assert "\n" not in str(info.value)


def test_csv_path_is_relative_to_the_case_file(tmp_path):
    (tmp_path / "slide.csv").write_text("time [s],slider_position [mm]\n0,0\n1,2\n")
    path = tmp_path / "measured.toml"
    path.write_text('[motion]\nprofile = "csv"\ncsv_file = "slide.csv"\n')
    case = load_case(str(path))
    assert case.motion.csv_file == os.path.abspath(tmp_path / "slide.csv")

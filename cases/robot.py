"""The paper's head moved by a robot arm: after the approach, four linear moves at 10 mm/s
around an 8 mm x 10 mm rectangle on a plane, each turning at a right angle at a corner
where the arm stops (exubrush/data/robot-path.csv: exubrush's illustration of such a
program, not a measured trajectory; docs/motion.md, "The powered-brush cases").

Run: ``python cases/robot.py [dfm|prb]``; results go to ``results/robot-MODEL``. To drive
the head along your own path, give a case file ``motion.pose_csv`` (docs/motion.md).
"""

import functools
import sys

from exubrush.simulation import run_case

run = functools.partial(run_case, "robot")
run.__doc__ = ("Simulate the robot-driven head on a plane: run(model='dfm', overrides=(), "
               "progress=True).")

if __name__ == "__main__":
    model = sys.argv[1] if len(sys.argv) > 1 else "dfm"
    print(f"saved to {run(model).save(f'results/robot-{model}')}")

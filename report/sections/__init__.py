"""The sections of REPORT.md, one module each; report/make_report.py puts them in order.

Each section function takes the JSON it is drawn from (and, where the section has figures, the
figure folder and its path relative to REPORT.md) and returns the section's lines; a section with
figures draws them as it writes the lines that show them. The race's scoring is the race
runner's, study/race_score.py: study/ goes on the path here, for sections/race*.py.
"""

import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__)))), "study"))

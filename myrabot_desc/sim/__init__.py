"""Built-in kinematic and diff-drive simulator for the seed's programs (``myrabot-desc sim``).

Modules: servo (the lab's servo units), diffdrive (twist -> wheels -> exact arcs),
arm (Pinocchio FK/IK, pointing), collide (coal), stability (tip-over margin),
scene (table and cans), the programs vuelta, escoja/seguir (pointing), drive,
result (verdict, JSON, CSV) and plot (Pillow); the command is commands/sim.py.
"""

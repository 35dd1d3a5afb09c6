"""Detectability of a ring crack from natural-frequency shifts (SI inside).

One concept per module: ``options`` (the scene's ``[detection]`` table),
``series`` (ring mounting in series with the FE ring body), ``model`` (the
crack's stiffnesses per depth), ``uncertainty`` (parameter scatter and FE error
for Monte Carlo), ``carrier`` (when the cracked tooth is in mesh, what a record
sees), ``pod`` (probability of detection), ``detectability`` (smallest detectable
depth against the mounting stiffness), ``study`` (the three together),
``measured`` (a CSV of identified frequencies), ``diagnosis`` (crack depth from
measured frequencies), ``numbers`` (round-off prints as 0), ``report`` and
``plots``.  Nothing heavy is imported here; matplotlib only in ``plots``.
"""

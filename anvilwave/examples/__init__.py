"""The example input files that ship with anvilwave (system files, anvils, soil, PDA records).

They are package data, so an installed wheel runs its own demo: ``anvilwave examples DIR``
copies them out (:func:`anvilwave.output.examples.copy_examples`), ``anvilwave demo`` reads Table 1
from here. Every path
inside them is relative to the file that names it (a hammer file under ``hammers/``, the
anvils under ``anvils/``), so the copy runs where it lands. The scripts (``script_api.py``,
``make_synthetic_*.py``, ``fmpy_cosim.py``) are examples to run, not modules to import.
"""

"""Analyses: impact, compare, drive, install, pda, match and batch.

Each analysis takes a system (or a record) and its settings, runs the engines, and returns a
documented result dataclass; the command line and the public API call them.
"""

"""Axisymmetric bodies as finite elements: geometry, mesh, linear elasticity, free-free modes,
CalculiX and the modal-data file.

The anvil, the modal ram and the pile-head tube share this layer.
"""

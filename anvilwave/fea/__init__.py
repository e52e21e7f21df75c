"""The reference FEA of the whole driving system: ram, anvil and pile as axisymmetric
explicit finite elements (quadratic triangles, lumped mass, central differences) with
compression-only node-to-node contacts (with Coulomb friction, and an optional anvil ring
between anvil and pile), against which the anvil ROM and the lumped mass are
compared.

Modules: :mod:`.bodies` (bodies, faces, contacts, section forces, static preload),
:mod:`.solver` (the explicit integrator), :mod:`.impact` (the ram-anvil-pile model and runs).
"""

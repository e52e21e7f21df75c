"""PDA: gauge records, the Case method and the physics of signal matching."""

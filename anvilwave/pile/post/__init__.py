"""Post-processing of blows: installation fatigue (S-N curves, rainflow, Miner) and force
spectra."""

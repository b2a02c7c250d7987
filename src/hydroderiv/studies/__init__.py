"""Studies: many conditions on one mesh (resistance sweeps, captive-test sweeps)."""

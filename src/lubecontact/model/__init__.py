"""The coupled contact: the model and its state, the fluid's film laws, evaluation,
force balance, Newton steps, the coupling loop, the effects decisions, validity, outputs
and ``solve`` (paper section 2.5, Fig. 1)."""

"""Validation gallery of the ECF project: regenerates, from the project's own code, the seed
dissertation's results that the model can produce (docs/validation/), with the seed's
statements checked by assertions. Entry point: `scripts/gallery.sh [--quick] [OUTDIR]`
(or `python -m gallery`)."""

"""``python -m cloth drape ...``: ``cloth.batch.drape`` from the command line, on a Dask
cluster with ``--dask ADDRESS``; what ``cloth drape --dask`` runs."""

from .batch import _main

raise SystemExit(_main())

"""Whole-map exchange formats: lossless INHerit-SG JSON and Spark-DSG (Hydra) JSON."""

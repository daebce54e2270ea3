"""What a run leaves: results and their files, plots, frames, the viewer, cleaning metrics,
comparison with measurements.
"""

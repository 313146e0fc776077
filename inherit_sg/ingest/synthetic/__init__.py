"""Procedural multi-floor houses, a ray-casting RGB-D renderer, exploration
trajectories, a perception noise model and an SQR-style query generator."""

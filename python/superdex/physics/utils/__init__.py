"""Helpers over the physics API (scene_helpers: finding actors by name, a ground plane)."""

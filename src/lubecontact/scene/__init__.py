"""Scenes: the validated, frozen description of one physical problem (docs/DESIGN.md
"Scene schema"); scene.py holds the schema, the YAML reader and the checks."""

from lubecontact.scene.scene import AUTO, SECTIONS, Scene, SceneError, load_scene, parse_override

__all__ = ["AUTO", "SECTIONS", "Scene", "SceneError", "load_scene", "parse_override"]

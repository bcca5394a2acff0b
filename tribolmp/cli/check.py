"""``tribolmp check SCENE.toml``: validate a scene file."""

from __future__ import annotations

HELP = "validate a scene file"


def configure(parser) -> None:
    """Add arguments."""
    parser.add_argument("scene", help="TOML scene file")
    parser.add_argument("--json", action="store_true", help="print the parsed scene as JSON")


def run(args) -> int:
    """Validate; print a summary (or JSON) and return 0, or raise SceneError."""
    from ..chain import plan_scene
    from ..chain.runner import preflight
    from ..scene import load_scene

    scene = load_scene(args.scene)
    # Everything `run` would refuse later is refused here: the plan (cross-stage rules) and
    # each running stage's preflight (files it reads, grids against memory, costs).
    plan = plan_scene(scene)
    notes = preflight(scene, plan)
    if args.json:
        from . import emit_json

        emit_json({"valid": True, "source": scene.source, "sections": scene.to_dict(),
                   "notes": notes})
    else:
        present = [k for k, v in scene.to_dict().items()]
        print(f"{args.scene}: OK ({', '.join(present)}); E* = {scene.effective_modulus:.4g} Pa")
        for line in notes:
            print(f"note: {line}")
    return 0

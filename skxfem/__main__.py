"""``python -m skxfem run scene.toml``: the same as the ``skxfem`` command."""
from .app.cli import main

if __name__ == "__main__":
    raise SystemExit(main())

"""``python -m skxfem run scene.toml``: the same as the ``skxfem`` command."""
from .cli import main

if __name__ == "__main__":
    raise SystemExit(main())

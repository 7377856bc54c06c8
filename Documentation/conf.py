# Sphinx configuration of LinkGI's documentation site. Built by scripts/docs.py (which
# copies Documentation/ into <build>/docs/src, generates the API reference and the gallery
# there, and runs sphinx-build -W); ctest runs it as docs.Site.
import os

project = "LinkGI"
author = "The LinkGI authors"
release = os.environ.get("LINKGI_VERSION", "")
version = release

extensions = ["myst_parser"]
source_suffix = {".md": "markdown", ".rst": "restructuredtext"}
master_doc = "index"
myst_heading_anchors = 4
# The records behind the measurements are data, linked from their READMEs, not pages.
exclude_patterns = ["_build", "**/*.json", "**/*.jsonl", "**/*.log", "**/*.txt", "**/*.sh",
                    "**/*.py"]

html_theme = "pydata_sphinx_theme"  # PyVista's theme
html_title = "LinkGI"
html_theme_options = {
    "show_prev_next": True,
    "navigation_depth": 2,
}
html_static_path = []


def _link_into_the_records(app, domain, node):
    """Links to a folder or a record file of the source tree (not a page) are kept as text,
    without a warning; a link to a missing page still warns."""
    target = node.get("reftarget", "")
    base = os.path.dirname(app.env.doc2path(node.get("refdoc", "index")))
    path = os.path.normpath(os.path.join(base, target.split("#")[0]))
    return True if target and os.path.exists(path) and not path.endswith(".md") else None


def setup(app):
    app.connect("warn-missing-reference", _link_into_the_records)

"""Sphinx configuration of tcpmsim's documentation site (issue 30).

Built by scripts/docs.sh, with warnings as errors, from build/docs-src: a copy of docs/ whose
notebooks docs/run_notebooks.py has executed with nbclient (nbsphinx renders them as stored and
executes nothing). Pages are MyST Markdown."""

project = "tcpmsim"
author = "the tcpmsim developers"
copyright = "2026, the tcpmsim developers"

extensions = ["myst_parser", "nbsphinx"]
source_suffix = {".md": "markdown"}
myst_heading_anchors = 3
myst_enable_extensions = ["dollarmath", "deflist"]
nbsphinx_execute = "never"

# matrices/: the hidden-effect matrices' records (JSON) and their README, read on GitHub.
exclude_patterns = ["_build", "**.ipynb_checkpoints", "matrices"]
html_theme = "furo"
html_title = "tcpmsim"
# Code blocks in languages Pygments does not lex strictly (a shell transcript, a YAML excerpt
# with an ellipsis) are shown as they are instead of failing the -W build.
highlight_language = "none"
suppress_warnings = ["misc.highlighting_failure"]

"""``embroact studio``: a designer in the browser, served on 127.0.0.1 by the command-line's own code.

:mod:`.session` holds the design being edited and answers the page (no web framework);
:mod:`.form` turns the design into fields and validates edits as the design file is;
:mod:`.views` renders what the page shows; :mod:`.outputs` confines writes to the output
directory; :mod:`.app` is the web server (Starlette, the optional ``studio`` extra) with
its token and Host checks; ``static/`` holds the page (plain HTML, JavaScript and CSS).
"""

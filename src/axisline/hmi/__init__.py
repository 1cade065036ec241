"""The web HMI of `axisline serve --http` (issue 17; docs/hmi.md).

    view.py     MachineView: the machine's read-outs and writes, run by the cycle at boundaries
    app.py      create_app: the pages, the JSON API and the WebSockets (FastAPI), endpoint side
    server.py   HmiServer: uvicorn in a thread of its own
    static/     the pages: plain HTML, CSS and small vanilla JS (no build step, no CDN)
    devices/    the device views of the personalities (sections the device page renders)
"""

"""pvpython client of the client/server test (see test_client_server.py):
connects to an MPI pvserver, loads the plugin on both sides, renders the
Distributed scene on the server ranks (remote rendering, IceT compositing),
compares it with the serial baseline, and selects cells."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from vtkrt_pv_scenes import *  # noqa: F401,F403

host, port, server_ranks = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
threshold = float(sys.argv[4]) if len(sys.argv) > 4 else 10.0
Connect(host, port)
check(servermanager.ActiveConnection.IsRemote(), "connected to pvserver at %s:%d" % (host, port))
load_plugin(remote=True)
view = ray_traced_view()
SetActiveView(view)
view.RemoteRenderThreshold = 0.0  # render on the server ranks, composite there
source, _ = mesh(view)
spheres, _ = glyphs(view, center=(0.0, 0.0, 0.0), radius=25.0)
place_camera(view, azimuth=-25.0, elevation=10.0)
Render(view)
process_ids = source.PointData["ProcessId"].GetRange()
check(process_ids == (0.0, float(server_ranks - 1)),
      "the mesh spans server ranks 0..%d (ProcessId range %s)" % (server_ranks - 1, process_ids))
png = os.path.join(TEMP_DIR, "paraview_Distributed_client_server.png")
os.makedirs(TEMP_DIR, exist_ok=True)
SaveScreenshot(png, view, ImageResolution=VIEW_SIZE)
compare_with_baseline(png, "paraview_Distributed", threshold)

# The server traced it: hard shadows, which only the tracer draws, change
# the image. (The view's counters live on the server; the client's copy of
# the view renders nothing in remote rendering.)
view.Shadows = 1
Render(view)
shadowed = os.path.join(TEMP_DIR, "paraview_Distributed_client_server_shadows.png")
SaveScreenshot(shadowed, view, ImageResolution=VIEW_SIZE)
difference = image_error(shadowed, png)
check(difference > 200, "shadows (ray traced on the server) change the image (error %.1f > 200)" % difference)
view.Shadows = 0

# A rubber band over the middle of the view selects cells of the mesh,
# through the server ranks' locators.
SetActiveSource(source)
SelectSurfaceCells(Rectangle=[190, 140, 210, 160], View=view)
selection = source.GetSelectionInput(0)
count = 0
if selection is not None:
    extract = ExtractSelection(Input=source, Selection=selection)
    extract.UpdatePipeline()
    count = extract.GetDataInformation().GetNumberOfCells()
check(10 <= count <= 441, "a 21x21-pixel rubber band on the mesh selects cells (got %d)" % count)
Disconnect()
finish()

"""The scene of one ParaView screenshot of ./splat docs (paraview --script): opens the file
SPLAT_SHOT_FILE with the reader ParaView picks, shows it with the representation
SPLAT_SHOT_REPRESENTATION (empty: the one Show picks) and frames it. scripts/docs.sh then dumps
the screen with xwd."""
import os

from paraview import simple

source = simple.OpenDataFile(os.environ["SPLAT_SHOT_FILE"])
view = simple.GetActiveViewOrCreate("RenderView")
view.OrientationAxesVisibility = 0
representation = os.environ.get("SPLAT_SHOT_REPRESENTATION")
if representation:
    simple.Show(source, view, Representation=representation)
else:
    simple.Show(source, view)
simple.ResetCamera(view)
simple.Render(view)

"""The scene of one ParaView screenshot of ./splat docs (paraview --script): opens the file
SPLAT_SHOT_FILE with the reader ParaView picks, shows it with the representation
SPLAT_SHOT_REPRESENTATION and frames it. scripts/docs.sh then dumps the screen with xwd."""
import os

from paraview import simple

source = simple.OpenDataFile(os.environ["SPLAT_SHOT_FILE"])
view = simple.GetActiveViewOrCreate("RenderView")
view.OrientationAxesVisibility = 0
simple.Show(source, view, Representation=os.environ["SPLAT_SHOT_REPRESENTATION"])
simple.ResetCamera(view)
simple.Render(view)

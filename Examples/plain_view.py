"""The look of the examples' (and the GUI test's) render views: no orientation axes, and a
background of our own instead of the colour palette's."""


def plain_view(view, background):
    """Hides the orientation axes of `view` and gives it the RGB `background`."""
    view.OrientationAxesVisibility = 0
    try:
        view.UseColorPaletteForBackground = 0  # ParaView >= 5.10: else Background is ignored
    except AttributeError:
        pass
    view.Background = background

namespace LaserEngrave.Core.Sweeps;

/// <summary>What each cell of a sweep burns, on its pixel grid.</summary>
public enum SweepPattern
{
    /// <summary>Every pixel: a filled square.</summary>
    Square,

    /// <summary>Every other pixel row: horizontal lines one pixel wide, one pixel apart.</summary>
    Lines,

    /// <summary>Every other pixel of every other row: isolated dots two pixels apart.</summary>
    Dots,

    /// <summary>A small image (<see cref="SweepSpec.CellImage"/>), its larger side the cell's side.</summary>
    Image,
}

namespace LaserEngrave.Core.Jobs;

/// <summary>How a layer of a job is burned.</summary>
public enum LayerMode
{
    /// <summary>An image, rastered (the image pipeline: mask, rows, timed switching).</summary>
    Raster,

    /// <summary>A drawing's paths as outlines.</summary>
    Outline,

    /// <summary>A drawing's closed shapes filled with scan lines (open paths as outlines).</summary>
    Fill,

    /// <summary>A drawing's shapes filled, then outlined.</summary>
    Both,
}

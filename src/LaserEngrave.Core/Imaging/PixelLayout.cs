namespace LaserEngrave.Core.Imaging;

/// <summary>How a <see cref="LoadedImage"/> keeps its pixels.</summary>
public enum PixelLayout
{
    /// <summary>Palette indices of 1, 2, 4 or 8 bits, packed leftmost pixel in the most significant bits of a byte.</summary>
    Indexed,

    /// <summary>Four bytes per pixel: red, green, blue, alpha.</summary>
    Rgba32,
}

namespace LaserEngrave.Core.Jobs;

/// <summary>Which size field the user set last, and so which one the others follow.</summary>
public enum SizeMode
{
    /// <summary>Width in mm; height follows the aspect.</summary>
    Width,

    /// <summary>Height in mm; width follows the aspect.</summary>
    Height,

    /// <summary>Both sides given, aspect unlocked.</summary>
    WidthAndHeight,

    /// <summary>Pixel pitch in µm (or microsteps per pixel).</summary>
    Pitch,
}

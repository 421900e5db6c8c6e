namespace LaserEngrave.Core.Marks;

/// <summary>How the lines of a text lie against each other: flush left, centred, or flush right.</summary>
public enum TextAlign
{
    Left,
    Center,
    Right,
}

namespace LaserEngrave.Core.Geometry;

/// <summary>Calibration measurements or a stored calibration that cannot be used; the message is one line saying why.</summary>
public sealed class CalibrationException : Exception
{
    public CalibrationException(string message)
        : base(message)
    {
    }

    public CalibrationException(string message, Exception inner)
        : base(message, inner)
    {
    }
}

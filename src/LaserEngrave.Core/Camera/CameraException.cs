namespace LaserEngrave.Core.Camera;

/// <summary>A camera measurement that cannot be made, in one line a technician can act on.</summary>
public sealed class CameraException : Exception
{
    public CameraException(string message)
        : base(message)
    {
    }
}

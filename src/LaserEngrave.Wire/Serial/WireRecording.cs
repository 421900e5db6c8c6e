using System.Text.Json;

namespace LaserEngrave.Wire.Serial;

/// <summary>One write or read of a <see cref="WireRecorder"/> file.</summary>
/// <param name="Seconds">Since the recorder started: when the host wrote, or when the bytes arrived.</param>
/// <param name="Stage">The stage's link (else the laser gate's).</param>
/// <param name="Write">Host to device (else device to host).</param>
/// <param name="Data">The bytes.</param>
public sealed record WireEvent(double Seconds, bool Stage, bool Write, byte[] Data)
{
    /// <summary>Not bytes but the start of this layer (from 0) of a job of layers, at <see cref="Seconds"/>; then no data.</summary>
    public int? Layer { get; init; }
}

/// <summary>Reads a flight recorder's file back, whole and checked: a truncated, cut-off or corrupt file is refused in one line.</summary>
public static class WireRecording
{
    /// <summary>The recording's events in file order; throws <see cref="WireRecordingException"/> naming the file and the problem.</summary>
    public static IReadOnlyList<WireEvent> Read(string path)
    {
        ArgumentException.ThrowIfNullOrWhiteSpace(path);
        string[] lines;
        try
        {
            lines = File.ReadAllLines(path);
        }
        catch (Exception ex) when (ex is FileNotFoundException or DirectoryNotFoundException)
        {
            throw new WireRecordingException($"{path}: the run's recording is missing", ex);
        }
        catch (Exception ex) when (ex is IOException or UnauthorizedAccessException)
        {
            throw new WireRecordingException($"{path}: cannot read the recording: {ex.Message}", ex);
        }

        if (lines.Length == 0 || lines[0] != "{\"wire\":1}")
        {
            throw new WireRecordingException($"{path}: not a LaserEngrave wire recording (its first line is not {{\"wire\":1}})");
        }

        var events = new List<WireEvent>(lines.Length);
        var previous = double.NegativeInfinity;
        for (var i = 1; i < lines.Length; i++)
        {
            var where = $"{path}: line {i + 1}";
            try
            {
                using var doc = JsonDocument.Parse(lines[i]);
                var root = doc.RootElement;
                if (root.TryGetProperty("truncated", out _))
                {
                    throw new WireRecordingException($"{where}: the recording is truncated (it reached its size cap), so the rest of the run is not in it and its burn cannot be replayed");
                }

                if (root.TryGetProperty("end", out var end))
                {
                    if (end.GetInt64() != events.Count || i != lines.Length - 1)
                    {
                        throw new WireRecordingException($"{where}: the end mark says {end.GetInt64()} events but {events.Count} precede it (or lines follow it): the recording is corrupt");
                    }

                    return events;
                }

                var seconds = root.GetProperty("t").GetDouble();
                if (root.TryGetProperty("layer", out var layer))
                {
                    // Noted by the host as a layer began, so on its clock as its writes are.
                    if (!double.IsFinite(seconds) || seconds < previous || layer.GetInt32() < 0)
                    {
                        throw new WireRecordingException($"{where}: not a layer's start (a time not before the writes after it, a layer from 0): the recording is corrupt");
                    }

                    previous = seconds;
                    events.Add(new WireEvent(seconds, false, false, []) { Layer = layer.GetInt32() });
                    continue;
                }

                var port = root.GetProperty("p").GetString();
                var direction = root.GetProperty("d").GetString();
                var data = Convert.FromHexString(root.GetProperty("x").GetString() ?? string.Empty);
                if (!double.IsFinite(seconds) || seconds < 0 || port is not ("s" or "l") || direction is not ("w" or "r") || data.Length == 0)
                {
                    throw new WireRecordingException($"{where}: not a recorded write or read (time, port s/l, direction w/r, bytes): the recording is corrupt");
                }

                // Writes are recorded in the order the host made them, so their times never go back.
                if (direction == "w" && seconds < previous)
                {
                    throw new WireRecordingException($"{where}: a write at {seconds} s before the one before it ({previous} s): the recording is corrupt");
                }

                previous = direction == "w" ? seconds : previous;
                events.Add(new WireEvent(seconds, port == "s", direction == "w", data));
            }
            catch (Exception ex) when (ex is JsonException or KeyNotFoundException or InvalidOperationException or FormatException)
            {
                throw new WireRecordingException($"{where}: not a recorded write or read ({ex.Message.Split('\n')[0]}): the recording is corrupt", ex);
            }
        }

        throw new WireRecordingException($"{path}: the recording has no end mark (the run's process was cut off while recording), so its burn cannot be replayed");
    }
}

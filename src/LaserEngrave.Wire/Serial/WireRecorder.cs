using System.Globalization;
using System.Text;

namespace LaserEngrave.Wire.Serial;

/// <summary>The flight recorder: every byte written to and read from the machine's links, with its time, as JSON lines.</summary>
/// <remarks>
/// <para>
/// One line a write or a read: <c>{"t":SECONDS,"p":"s"|"l","d":"w"|"r","x":"HEX"}</c>, <c>t</c> the seconds since the
/// recorder started on its clock (a write: when the host wrote; a read: when the bytes arrived), <c>p</c> the stage or
/// laser link; <c>{"t":SECONDS,"layer":N}</c> where layer N (from 0) of a job of layers begins, so a replay checks each
/// layer's burn alone. The file starts with <c>{"wire":1}</c> and ends with <c>{"end":EVENTS}</c>, or with <c>{"truncated":EVENTS}</c>
/// when it reached its cap (the rest of the run is then not in it); a file with neither was cut off (the process died).
/// </para>
/// <para>Thread-safe: the host writes on its thread and each link's reader loop records its arrivals on its own.</para>
/// </remarks>
public sealed class WireRecorder : IDisposable
{
    /// <summary>The file's cap: a 5 mm QR's run is about 0.2 MB (3,200 writes and reads); a longer run keeps its start.</summary>
    public const long DefaultCapBytes = 8L * 1024 * 1024;

    private readonly Lock _sync = new();
    private readonly TimeProvider _time;
    private readonly long _start;
    private readonly long _capBytes;
    private readonly StreamWriter _writer;
    private readonly StringBuilder _line = new();
    private long _bytes;
    private long _events;
    private bool _truncated;
    private bool _finished;
    private bool _failed;

    /// <param name="path">The file, created new.</param>
    /// <param name="time">The clock of the times recorded.</param>
    /// <param name="capBytes">The file's largest size; past it the file ends with the truncated mark.</param>
    public WireRecorder(string path, TimeProvider time, long capBytes = DefaultCapBytes)
    {
        ArgumentException.ThrowIfNullOrWhiteSpace(path);
        ArgumentNullException.ThrowIfNull(time);
        Path = System.IO.Path.GetFullPath(path);
        _time = time;
        _capBytes = capBytes;
        _writer = new StreamWriter(new FileStream(Path, FileMode.CreateNew, FileAccess.Write, FileShare.Read), new UTF8Encoding(false)) { NewLine = "\n" };
        _writer.WriteLine("{\"wire\":1}");
        _bytes = 11;
        _start = time.GetTimestamp();
    }

    /// <summary>The recording's full path.</summary>
    public string Path { get; }

    /// <summary>A link that records what passes through <paramref name="link"/>; <paramref name="stage"/> says which link it is.</summary>
    public ISerialLink Wrap(ISerialLink link, bool stage) => new RecordingLink(link, this, stage ? 's' : 'l');

    /// <summary>Notes that layer <paramref name="index"/> (from 0) of a job of layers begins now.</summary>
    public void MarkLayer(int index)
    {
        ArgumentOutOfRangeException.ThrowIfNegative(index);
        Append(null, (seconds, line) => line.Append(CultureInfo.InvariantCulture, $"{{\"t\":{seconds:0.0000000},\"layer\":{index}}}"));
    }

    /// <summary>Ends the file with its end (or truncated) mark and closes it; what the run log says of it.</summary>
    public WireRecordingSummary Finish()
    {
        lock (_sync)
        {
            if (!_finished)
            {
                _finished = true;
                try
                {
                    if (!_truncated && !_failed)
                    {
                        _writer.WriteLine(string.Create(CultureInfo.InvariantCulture, $"{{\"end\":{_events}}}"));
                    }

                    _writer.Dispose();
                }
                catch (IOException)
                {
                    // Without its end mark replay calls the file cut off; the run's log is written all the same.
                }
            }

            return new WireRecordingSummary(System.IO.Path.GetFileName(Path), _events, _truncated);
        }
    }

    public void Dispose() => Finish();

    /// <summary>Closes and deletes the file: the ports never opened, so there is no run to go with it.</summary>
    public void Discard()
    {
        Finish();
        File.Delete(Path);
    }

    private void Record(char port, char direction, long? timestamp, ReadOnlySpan<byte> data)
    {
        if (data.IsEmpty)
        {
            return;
        }

        var hex = Convert.ToHexString(data);
        Append(timestamp, (seconds, line) =>
        {
            line.Append(CultureInfo.InvariantCulture, $"{{\"t\":{seconds:0.0000000},\"p\":\"{port}\",\"d\":\"{direction}\",\"x\":\"");
            line.Append(hex);
            line.Append("\"}");
        });
    }

    // One event's line, at its time (null: now, stamped under the lock), unless the recording has ended, failed or
    // reached its cap.
    private void Append(long? timestamp, Action<double, StringBuilder> write)
    {
        lock (_sync)
        {
            if (_finished || _failed || _truncated)
            {
                return;
            }

            // Writes and layer marks are stamped here, under the lock: the stage's and the gate's writers run on their own
            // threads, and a stamp taken before the lock could be appended after a later one (a recording replay then
            // refused as corrupt: a ports run at 15:00 on 2026-11-29 had two writes 4 µs out of order).
            var seconds = ((timestamp ?? _time.GetTimestamp()) - _start) / (double)_time.TimestampFrequency;
            _line.Clear();
            write(seconds, _line);
            if (_bytes + _line.Length + 1 > _capBytes)
            {
                _truncated = true;
                try
                {
                    _writer.WriteLine(string.Create(CultureInfo.InvariantCulture, $"{{\"truncated\":{_events}}}"));
                    _writer.Flush();
                }
                catch (IOException)
                {
                    // The record says truncated all the same.
                }

                return;
            }

            try
            {
                _writer.WriteLine(_line);
            }
            catch (IOException)
            {
                // A full disk must not stop the run: the recording stops, and without its end mark replay calls it cut off.
                _failed = true;
                return;
            }

            _bytes += _line.Length + 1;
            _events++;
        }
    }

    private sealed class RecordingLink(ISerialLink inner, WireRecorder recorder, char port) : ISerialLink
    {
        public string Name => inner.Name;

        public bool HasUnreadBytes => inner.HasUnreadBytes;

        public async ValueTask<int> ReadAsync(Memory<byte> buffer, CancellationToken cancellationToken) =>
            (await ReadStampedAsync(buffer, recorder._time, cancellationToken)).Count;

        public async ValueTask<StampedRead> ReadStampedAsync(Memory<byte> buffer, TimeProvider time, CancellationToken cancellationToken)
        {
            var read = await inner.ReadStampedAsync(buffer, time, cancellationToken);
            recorder.Record(port, 'r', StampedRead.OnClock(read.ArrivalTimestamp, time, recorder._time), buffer.Span[..read.Count]);
            return read;
        }

        public async ValueTask WriteAsync(ReadOnlyMemory<byte> data, CancellationToken cancellationToken)
        {
            // The time the host wrote (stamped as it is appended, so writes on the two ports stay in order), before the
            // write may block behind the port's buffer.
            recorder.Record(port, 'w', null, data.Span);
            await inner.WriteAsync(data, cancellationToken);
        }

        public ValueTask DisposeAsync() => inner.DisposeAsync();
    }
}

/// <summary>What a finished recording is: its file's name (in the log's folder), its events and whether it reached its
/// size cap. The run log keeps the same three facts as its <c>recording</c> member.</summary>
public sealed record WireRecordingSummary(string File, long Events, bool Truncated);
